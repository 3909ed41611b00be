// rank_ledger.cpp — the per-rank flight recorder and its post-mortem (rank_ledger.hpp).
#include "distributed/rank_ledger.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace frontsteal::mpi {
namespace {

constexpr char kMagic[8] = {'F', 'S', 'L', 'E', 'D', 'G', '1', '\0'};

// The file: this header, then one byte per item.
struct Header {
  char magic[8];
  std::int32_t rank, ranks, pid;
  std::uint32_t items;
  std::int32_t frame;       // atomic_ref: the frame in progress (-1 before the first)
  std::int32_t frame_done;  // atomic_ref: 1 once past the frame's done barrier
  std::int32_t state;       // atomic_ref: LedgerState
  std::int32_t pad;
  std::uint64_t ran;  // atomic_ref: items this rank ran in the current frame
  char scheduler[32];
};

Header* g_header = nullptr;
std::uint8_t* g_bytes = nullptr;

template <class T>
void store(T& field, T value) noexcept {
  std::atomic_ref<T>(field).store(value, std::memory_order_relaxed);
}

extern "C" void record_sigterm(int sig) {
  if (g_header != nullptr) store(g_header->state, static_cast<std::int32_t>(LedgerState::kTerminated));
  signal(sig, SIG_DFL);  // async-signal-safe: then die of the signal as before
  raise(sig);
}

std::string rank_file(const std::string& dir, int rank) { return dir + "/rank-" + std::to_string(rank) + ".ledger"; }

void append_run(RangeList& out, ItemId id) { append_merging(out, {id, id + 1}); }

std::string items(std::uint64_t n) { return std::to_string(n) + (n == 1 ? " item" : " items"); }

std::string ranges_text(const RangeList& r, std::size_t max_ranges) {
  std::string s;
  for (std::size_t k = 0; k < r.size() && k < max_ranges; ++k) {
    s += (k ? ", " : "") + std::to_string(r[k].begin) +
         (r[k].size() > 1 ? "-" + std::to_string(r[k].end - 1) : std::string());
  }
  if (r.size() > max_ranges) s += ", ... (" + std::to_string(r.size() - max_ranges) + " more ranges)";
  return s;
}

}  // namespace

const char* to_string(LedgerState s) noexcept {
  switch (s) {
    case LedgerState::kRunning: return "no exit recorded";
    case LedgerState::kFinished: return "finished";
    case LedgerState::kWatchdog: return "ended by its watchdog";
    case LedgerState::kTerminated: return "terminated (SIGTERM, the launcher ending the job)";
  }
  return "?";
}

void open_ledger(const std::string& dir, int rank, int ranks, ItemId n) {
  if (dir.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string path = rank_file(dir, rank);
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("--ledger: cannot create " + path + ": " + std::strerror(errno));
  const std::size_t size = sizeof(Header) + n;
  if (::ftruncate(fd, static_cast<off_t>(size)) != 0) {
    ::close(fd);
    throw std::runtime_error("--ledger: cannot size " + path + ": " + std::strerror(errno));
  }
  void* p = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (p == MAP_FAILED) throw std::runtime_error("--ledger: cannot map " + path + ": " + std::strerror(errno));
  auto* h = static_cast<Header*>(p);
  std::memcpy(h->magic, kMagic, sizeof kMagic);
  h->rank = rank;
  h->ranks = ranks;
  h->pid = static_cast<std::int32_t>(::getpid());
  h->items = n;
  h->frame = -1;
  h->frame_done = 0;
  h->state = static_cast<std::int32_t>(LedgerState::kRunning);
  g_bytes = static_cast<std::uint8_t*>(p) + sizeof(Header);
  g_header = h;
  struct sigaction sa {};
  sa.sa_handler = record_sigterm;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGTERM, &sa, nullptr);
}

void ledger_begin_frame(int frame, std::string_view scheduler) noexcept {
  if (g_header == nullptr) return;
  store(g_header->frame_done, 0);
  std::memset(g_bytes, 0, g_header->items);
  store(g_header->ran, std::uint64_t{0});
  std::memset(g_header->scheduler, 0, sizeof g_header->scheduler);
  std::memcpy(g_header->scheduler, scheduler.data(), std::min(scheduler.size(), sizeof g_header->scheduler - 1));
  std::atomic_ref<std::int32_t>(g_header->frame).store(frame, std::memory_order_release);
}

void ledger_mark(ItemId id) noexcept {
  if (g_header == nullptr) return;
  std::atomic_ref<std::uint8_t>(g_bytes[id]).store(1, std::memory_order_relaxed);
  std::atomic_ref<std::uint64_t>(g_header->ran).fetch_add(1, std::memory_order_relaxed);
}

void ledger_frame_done() noexcept {
  if (g_header != nullptr) store(g_header->frame_done, 1);
}

void ledger_exit(LedgerState state) noexcept {
  if (g_header != nullptr) store(g_header->state, static_cast<std::int32_t>(state));
}

PostMortem read_ledgers(const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error("--post-mortem: no directory " + dir);
  PostMortem pm;
  for (int r = 0;; ++r) {
    const std::string path = rank_file(dir, r);
    if (!std::filesystem::exists(path)) {
      if (r == 0) throw std::runtime_error("--post-mortem: no rank-0.ledger in " + dir + " (was --ledger given?)");
      break;
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Header h{};
    if (bytes.size() < sizeof h) throw std::runtime_error("--post-mortem: " + path + " is truncated");
    std::memcpy(&h, bytes.data(), sizeof h);
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || bytes.size() != sizeof h + h.items)
      throw std::runtime_error("--post-mortem: " + path + " is not a frontsteal-mpi ledger");
    LedgerRecord rec;
    rec.rank = h.rank;
    rec.ranks = h.ranks;
    rec.pid = h.pid;
    rec.frame = h.frame;
    rec.frame_done = h.frame_done != 0;
    rec.state = static_cast<LedgerState>(h.state);
    rec.scheduler.assign(h.scheduler, strnlen(h.scheduler, sizeof h.scheduler));
    rec.ran = h.ran;
    rec.by.assign(bytes.begin() + sizeof h, bytes.end());
    pm.items = h.items;
    pm.ranks.push_back(std::move(rec));
  }
  if (static_cast<int>(pm.ranks.size()) != pm.ranks.front().ranks)
    throw std::runtime_error("--post-mortem: " + dir + " holds " + std::to_string(pm.ranks.size()) +
                             " ledgers, the job had " + std::to_string(pm.ranks.front().ranks) + " ranks");
  pm.clean = std::all_of(pm.ranks.begin(), pm.ranks.end(),
                         [](const LedgerRecord& r) { return r.state == LedgerState::kFinished; });
  for (const LedgerRecord& r : pm.ranks) {
    if (r.frame > pm.frame) {
      pm.frame = r.frame;
      pm.scheduler = r.scheduler;
    }
    if (r.state == LedgerState::kRunning) pm.died.push_back(r.rank);
  }
  if (pm.clean || pm.frame < 0) return pm;
  for (ItemId id = 0; id < pm.items; ++id) {
    bool survivor = false, dead = false;
    for (const LedgerRecord& r : pm.ranks) {
      if (r.frame != pm.frame || r.by[id] == 0) continue;
      (r.state == LedgerState::kRunning ? dead : survivor) = true;
    }
    if (!survivor && !dead) {
      append_run(pm.never_ran, id);
      ++pm.never_ran_count;
    } else if (!survivor) {
      append_run(pm.only_dead_ran, id);
      ++pm.only_dead_ran_count;
    }
  }
  return pm;
}

std::string describe(const PostMortem& pm) {
  if (pm.clean) return "post-mortem: every rank finished normally; nothing was lost\n";
  std::string s = "post-mortem: the job ended in frame " + std::to_string(pm.frame) + " (" + pm.scheduler + ")";
  if (pm.died.empty()) {
    s += "; no rank died without a recorded exit\n";
  } else {
    s += "; rank" + std::string(pm.died.size() > 1 ? "s" : "");
    for (std::size_t k = 0; k < pm.died.size(); ++k) s += (k ? ", " : " ") + std::to_string(pm.died[k]);
    s += " died (no exit recorded)\n";
  }
  s += "  lost: " + std::to_string(pm.never_ran_count) + " of " + items(pm.items) + " of frame " +
       std::to_string(pm.frame) + " never ran" + (pm.never_ran_count ? ": " + ranges_text(pm.never_ran, 8) : "") + "\n";
  s += "  lost with the dead: " + items(pm.only_dead_ran_count) +
       " ran only on a rank that died (their results died with it)" +
       (pm.only_dead_ran_count ? ": " + ranges_text(pm.only_dead_ran, 8) : "") + "\n";
  for (const LedgerRecord& r : pm.ranks) {
    s += "  rank " + std::to_string(r.rank) + " (pid " + std::to_string(r.pid) + "): " + to_string(r.state) +
         "; frame " + std::to_string(r.frame) + (r.frame_done ? " done, waiting for the others" : " in progress") +
         ", " + items(r.ran) + " run in it\n";
  }
  return s;
}

}  // namespace frontsteal::mpi
