// hierarchical_rank.cpp — ranks x threads (hierarchical_rank.hpp).
#include "distributed/hierarchical_rank.hpp"

#include <algorithm>
#include <chrono>
#include <random>

#include "distributed/idle_backoff.hpp"
#include "distributed/rank_ledger.hpp"
#include "distributed/rank_watchdog.hpp"
#include "distributed/refill_budget.hpp"

namespace frontsteal::mpi {
namespace {

using Clock = std::chrono::steady_clock;

// The largest chunk a worker takes from the rank list at once: a chunk is no longer stealable by other ranks.
constexpr std::uint32_t kMaxChunk = 256;
// Remote victims tried per round before the rank re-reads the global count (A3) and backs off: with hundreds of
// ranks a round over all of them delays the frame's end by hundreds of one-sided operations (Saraswat et al.'s
// w random steals before going quiet).
constexpr std::size_t kVictimsPerRound = 8;
// A rank waiting on its lifelines probes random victims after this long, then at doubling intervals up to the last.
constexpr std::chrono::microseconds kLifelineProbeFirst{1000}, kLifelineProbeLast{16000};

}  // namespace

struct HierarchicalRank::Worker {
  Worker(std::uint32_t t, LocalSlot& slot, ActiveWorkers<StdBackend, Fenced>& active, std::uint32_t capacity)
      : index(t), owner(slot), thief(active, capacity) {}
  std::uint32_t index;
  Owner<StdBackend, Fenced> owner;
  Thief<StdBackend, Fenced> thief;
  std::vector<std::uint32_t> local_victims;
  RangeList log, chunk;
  bool holding = false;   // counts in local_active_
  RefillHistory history;  // this frame's: what its next refill prices unknown items with, and caps them by
  double busy_s = 0, items = 0, local_steals = 0;
  std::uint64_t triangles = 0;
};

HierarchicalRank::HierarchicalRank(const Options& o, Workload& wl, int rank, WindowProtocol& window,
                                   std::vector<int> remote_victims, double owner_progress_us, Lifelines* lifelines,
                                   HierFaultHooks faults)
    : o_(o),
      wl_(wl),
      rank_(rank),
      window_(window),
      remote_victims_(std::move(remote_victims)),
      progress_(MPI_COMM_WORLD, owner_progress_us),
      threads_(static_cast<std::uint32_t>(std::max(1, o.threads))),
      local_active_(0),
      start_(static_cast<std::ptrdiff_t>(threads_)),
      end_(static_cast<std::ptrdiff_t>(threads_)) {
  lifelines_ = lifelines;
  item_costs_.assign(wl.n, 0.0f);
  last_costs_.assign(wl.n, 0.0f);
  faults_ = std::move(faults);
  // A local list holds a chunk or a share of one: at most kMaxChunk ranges.
  for (std::uint32_t t = 0; t < threads_; ++t) slots_.push_back(std::make_unique<LocalSlot>(kMaxChunk));
  std::mt19937_64 rng(0x51ED270B27ull * static_cast<std::uint64_t>(rank + 1));
  for (std::uint32_t t = 0; t < threads_; ++t) {
    workers_.push_back(std::make_unique<Worker>(t, *slots_[t], local_active_, kMaxChunk));
    for (std::uint32_t v = 0; v < threads_; ++v) {
      if (v != t) workers_.back()->local_victims.push_back(v);
    }
    std::shuffle(workers_.back()->local_victims.begin(), workers_.back()->local_victims.end(), rng);
  }
  for (std::uint32_t t = 1; t < threads_; ++t) threads_started_.emplace_back([this, t] { worker_main(t); });
}

HierarchicalRank::~HierarchicalRank() {
  stop_.store(true, std::memory_order_relaxed);  // ordered before the workers' read by the barrier
  start_.arrive_and_wait();
  for (std::thread& t : threads_started_) t.join();
}

void HierarchicalRank::worker_main(std::uint32_t t) {
  while (true) {
    start_.arrive_and_wait();
    if (stop_.load(std::memory_order_relaxed)) return;
    work(t);
    end_.arrive_and_wait();
  }
}

void HierarchicalRank::run_frame(int frame, std::vector<std::uint32_t>& counts, std::uint64_t& triangles,
                                 RangeList& log) {
  frame_ = frame;
  counts_ = &counts;
  // The refills' price list: the costs the caller handed over (hier-seeded: every rank's), else this rank's own
  // times of the last frame (the items of its list; 0 for the others: refill_budget.hpp prices them).
  if (shared_costs_given_) {
    shared_costs_given_ = false;
  } else {
    last_costs_.swap(item_costs_);
  }
  std::fill(item_costs_.begin(), item_costs_.end(), 0.0f);
  rank_active_ = true;  // E4 re-armed the window's count with every rank in it
  waiting_ = false;
  first_item_done_.store(false, std::memory_order_relaxed);
  dry_reported_ = false;
  frame_over_.store(false, std::memory_order_relaxed);
  for (auto& w : workers_) {
    w->log.clear();
    w->triangles = 0;
    w->history = {};
  }
  start_.arrive_and_wait();  // the frame's state above happens-before every worker's loop
  work(0);
  end_.arrive_and_wait();  // every worker's items and logs happen-before what follows
  // The rank's next list: every item its workers ran, in id order.
  RangeList all;
  for (auto& w : workers_) {
    all.insert(all.end(), w->log.begin(), w->log.end());
    triangles += w->triangles;
  }
  std::sort(all.begin(), all.end(), [](const IdRange& a, const IdRange& b) { return a.begin < b.begin; });
  log.clear();
  for (const IdRange& r : all) append_merging(log, r);
}

void HierarchicalRank::work(std::uint32_t t) {
  Worker& w = *workers_[t];
  std::uint32_t failed_rounds = 0;
  while (!frame_over_.load(std::memory_order_acquire)) {
    // 1. Its own local list.
    while (const std::optional<ItemId> id = w.owner.try_claim()) execute(w, *id);
    if (w.holding) {
      local_active_.leave();  // A2 (local): own list exhausted, every claimed item done
      w.holding = false;
    }
    // 2. A chunk of the rank's list (the rank's own work, claimed under the mutex: cheaper than a steal).
    bool got = refill(w);
    // 3. A sibling's local list: node-local victims before any remote one.
    for (std::size_t k = 0; !got && k < w.local_victims.size(); ++k) {
      if (w.thief.try_steal(*slots_[w.local_victims[k]]) != StealOutcome::kStolen) continue;  // A1 (local) inside
      w.owner.install(w.thief.share());
      w.holding = true;
      w.local_steals += 1;
      got = true;
    }
    if (got) {
      failed_rounds = 0;
      continue;
    }
    // 4. Nothing in this rank for this worker: worker 0 goes to other ranks once every local worker is dry.
    if (t == 0) {
      if (!remote_step(failed_rounds)) return;
    } else {
      idle_wait(++failed_rounds);
    }
  }
}

// Claims items from the rank list into w's local list until they are worth --chunk-us by the last frame's times,
// items without one admitted as refill_budget.hpp says (priced by this worker's last item, their number capped),
// at most kMaxChunk: by measured cost, not by count, so that a hot region's heavy items stay in the rank list,
// stealable by other ranks. With --batch-claims on, one owner handshake per run of consecutive ids (the rank's
// claims are serialized by the mutex, so the time saved is every sibling's); off, one per item. The join comes
// first (under the mutex), so worker 0 never sees the local count at 0 while a chunk is on its way to a worker.
bool HierarchicalRank::refill(Worker& w) {
  w.chunk.clear();
  {
    std::lock_guard<std::mutex> lock(rank_mutex_);
    local_active_.join();  // A1 (local)
    const auto known_ns = [&](ItemId id) {
      const float known = last_costs_[id];
      return known > 0 ? 1e9 * double{known} : -1.0;
    };
    RefillBudget budget(o_.chunk_us * 1e3, kMaxChunk, w.history, window_.unclaimed(), threads_);
    if (o_.batch_claims) {
      // One handshake per run of consecutive ids: the run's ids the budget admits (at least one).
      while (true) {
        const IdRange run = window_.unclaimed_run();
        std::uint32_t n = 0;
        while (run.begin + n < run.end && budget.admit(known_ns(run.begin + n))) ++n;
        if (n == 0) break;
        const std::optional<IdRange> ids = window_.try_claim_up_to(n);
        if (!ids) break;
        append_merging(w.chunk, *ids);
        if (ids->size() < n) break;  // End fell below the run: the rest of the list was stolen
      }
    } else {
      // One handshake per item; the next item's id is the one at Front (unclaimed_run), priced before the claim.
      while (true) {
        const IdRange run = window_.unclaimed_run();
        if (run.empty() || !budget.admit(known_ns(run.begin))) break;
        const std::optional<ItemId> id = window_.try_claim();
        if (!id) break;
        append_merging(w.chunk, {*id, *id + 1});
      }
    }
    if (w.chunk.empty()) {
      local_active_.leave();
      return false;
    }
    std::uint32_t taken = 0;
    for (const IdRange& r : w.chunk) taken += r.size();
    w.history.last_refill = taken;
  }
  w.owner.install(w.chunk);
  w.holding = true;
  return true;
}

// Worker 0, its rank list empty and nothing local for it. Returns false when the frame is over.
bool HierarchicalRank::remote_step(std::uint32_t& failed_rounds) {
  idle_start_ = Clock::now();
  const auto account = [&] { idle_s_ += std::chrono::duration<double>(Clock::now() - idle_start_).count(); };
  {
    std::lock_guard<std::mutex> lock(rank_mutex_);
    if (!local_active_.all_idle()) {              // a sibling still holds work: it may yet be stolen locally
      if (progress_.enabled()) progress_.call();  // thieves' operations on this rank's window wait for it (TCP)
      idle_back_off(++failed_rounds);
      account();
      return true;
    }
  }
  if (rank_active_) {
    if (faults_.rank_dry && !dry_reported_) faults_.rank_dry();  // the first time this frame
    dry_reported_ = true;
    window_.leave();  // A2 for the rank: its list exhausted, every local worker dry
    rank_active_ = false;
  }
  if (waiting_) {
    const bool more = lifeline_wait(failed_rounds);
    account();
    return more;
  }
  if (window_.all_idle()) return end_frame(true);  // A3: no rank holds work
  const std::size_t round = std::min(kVictimsPerRound, remote_victims_.size());
  for (std::size_t k = 0; k < round; ++k) {
    if (try_remote(remote_victims_[next_victim_++ % remote_victims_.size()]) == StealOutcome::kStolen) {
      failed_rounds = 0;
      account();
      return true;
    }
  }
  if (lifelines_ != nullptr) {  // quiet from here: register, read the count once more (L1), wait
    lifelines_->register_hungry();
    if (window_.all_idle()) return end_frame(true);
    begin_waiting();
    failed_rounds = 0;
  } else {
    idle_back_off(++failed_rounds);
  }
  note_progress();
  account();
  return true;
}

// Worker 0, registered at its lifelines: the frame's end or an invitation, read from its own window words.
bool HierarchicalRank::lifeline_wait(std::uint32_t& failed_rounds) {
  if (lifelines_->notice_seen()) return end_frame(false);
  if (const std::optional<int> donor = lifelines_->new_invitation()) {
    waiting_ = false;
    if (try_remote(*donor) == StealOutcome::kStolen) {
      failed_rounds = 0;
      return true;
    }
    lifelines_->register_hungry();  // the donor ran dry first: a new registration, then the count (L1)
    if (window_.all_idle()) return end_frame(true);
    begin_waiting();
    return true;
  }
  // A donor the OS has stopped cannot invite (a --slow rank runs 1 ms in 10), but its list can still be stolen
  // one-sidedly: after kLifelineProbeFirst of waiting, and then at doubling intervals, one round of random
  // victims. Rare enough not to be the polling lifelines replace. The count is read again only if the round
  // left it (L1: a share that came out empty is an A1 and an A2); a round that found every list empty left
  // nothing, and the frame's end still comes by the notice (so the notice's control still hangs without it).
  if (Clock::now() >= next_probe_) {
    probe_interval_ = std::min<Clock::duration>(2 * probe_interval_, kLifelineProbeLast);
    next_probe_ = Clock::now() + probe_interval_;
    bool left = false;
    const std::size_t round = std::min(kVictimsPerRound, remote_victims_.size());
    for (std::size_t k = 0; k < round; ++k) {
      const StealOutcome out = try_remote(remote_victims_[next_victim_++ % remote_victims_.size()]);
      if (out == StealOutcome::kStolen) {
        waiting_ = false;
        failed_rounds = 0;
        return true;
      }
      left = left || out == StealOutcome::kSkippedAll;
    }
    if (left && window_.all_idle()) return end_frame(true);
  }
  if (progress_.enabled()) progress_.call();  // other ranks' operations on this rank's window (TCP)
  idle_back_off(++failed_rounds, true, kLifelineWaitCapUs);
  note_progress();
  return true;
}

void HierarchicalRank::begin_waiting() {
  waiting_ = true;
  probe_interval_ = kLifelineProbeFirst;
  next_probe_ = Clock::now() + probe_interval_;
}

StealOutcome HierarchicalRank::try_remote(int victim) {
  StealHooks hooks;
  hooks.force_overlap = o_.force_overlap;  // tests only: the interleaving a skipped re-read gets wrong, forced
  const auto t0 = Clock::now();
  remote_attempts_ += 1;
  const StealOutcome out = window_.try_steal(victim, hooks);  // A1 (global) inside, on success
  if (out != StealOutcome::kStolen) return out;
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  remote_steals_ += 1;
  steal_latency_s_ += s;
  steal_latency_max_s_ = std::max(steal_latency_max_s_, s);
  steal_latencies_us_.push_back(1e6 * s);
  {
    std::lock_guard<std::mutex> lock(rank_mutex_);
    window_.install(window_.share());
  }
  wake_workers();
  rank_active_ = true;
  return StealOutcome::kStolen;
}

bool HierarchicalRank::end_frame(bool from_count) {
  frame_over_.store(true, std::memory_order_release);
  wake_workers();
  if (lifelines_ != nullptr) lifelines_->tell_frame_over(from_count);
  idle_s_ += std::chrono::duration<double>(Clock::now() - idle_start_).count();
  return false;
}

// The back-off schedule of idle_backoff.hpp, capped at sibling_backoff_cap_us(), cut short by wake_workers().
void HierarchicalRank::idle_wait(std::uint32_t failed_rounds) {
  if (failed_rounds < 4) return std::this_thread::yield();
  const auto pause = std::chrono::microseconds(std::min<std::uint32_t>(
      1u << std::min<std::uint32_t>(failed_rounds - 4, 8), sibling_backoff_cap_us(o_.chunk_us)));
  std::unique_lock<std::mutex> lock(wake_mutex_);
  const std::uint64_t seen = wake_generation_;
  wake_.wait_for(lock, pause, [&] { return wake_generation_ != seen; });
}

void HierarchicalRank::use_costs(const std::vector<float>& costs) {
  last_costs_ = costs;
  shared_costs_given_ = true;
}

void HierarchicalRank::wake_workers() {
  if (threads_ < 2) return;
  {
    std::lock_guard<std::mutex> lock(wake_mutex_);
    ++wake_generation_;
  }
  wake_.notify_all();
}

void HierarchicalRank::execute(Worker& w, ItemId id) {
  const auto t0 = Clock::now();
  w.triangles += wl_.run_on(frame_, id, w.index);
  std::atomic_ref<std::uint32_t>((*counts_)[id]).fetch_add(1, std::memory_order_relaxed);
  ledger_mark(id);
  const double took = std::chrono::duration<double>(Clock::now() - t0).count();
  if (!item_costs_.empty()) item_costs_[id] = static_cast<float>(took);  // each id runs once: no two writers
  w.busy_s += took;
  w.items += 1;
  w.history.last_item_ns = took * 1e9;
  if (w.index == 0 && progress_.maybe_call(Clock::now())) progress_calls_ += 1;  // only worker 0 calls MPI
  if (w.index == 0 && lifelines_ != nullptr) {  // a donor: invite the ranks registered here, while it has spare
    lifelines_->invite_hungry([this] {
      std::lock_guard<std::mutex> lock(rank_mutex_);
      return window_.unclaimed() >= 2;
    });
  }
  // --die and --slow act after the rank's first item of the frame, whichever thread runs it: with threads of
  // several ranks sharing few cores, the main thread may run no item in a frame (its siblings and other ranks'
  // thieves took the rank's list while it waited for a core), and the fault must still come.
  if (!first_item_done_.load(std::memory_order_relaxed) && !first_item_done_.exchange(true)) {
    if (faults_.first_item) faults_.first_item(frame_);
  }
  append_merging(w.log, {id, id + 1});
  note_progress();
}

void HierarchicalRank::add_stats(RankStats& s) const {
  for (const auto& w : workers_) {
    s.busy_s += w->busy_s;
    s.items += w->items;
    s.local_steals += w->local_steals;
  }
  s.steals += remote_steals_;
  s.steal_attempts += remote_attempts_;
  s.steal_latency_s += steal_latency_s_;
  s.steal_latency_max_s = std::max(s.steal_latency_max_s, steal_latency_max_s_);
  s.idle_s += idle_s_;
  s.progress_calls += progress_calls_;
}

}  // namespace frontsteal::mpi
