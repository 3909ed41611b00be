// frontsteal-mpi — the main job across MPI ranks (issue 18, paper §7): the same frame loop as frontsteal, with
// every rank holding the read-only workload and tessellating its items of each frame, under four schedulers:
//   rma       load stealing with each rank's slot in an MPI-3 window (rma_stealing.hpp): the owner claims
//             locally, thieves steal with one-sided Get/Put/CAS; the busy rank never answers anyone.
//   request   request-based stealing (§7: "request based load stealing, but overhead on the busy processors
//             must increase"): an idle rank sends a steal request; the busy owner polls (MPI_Iprobe) between
//             items and replies with the second half of its remaining list.
//   central   a central counter in rank 0's window (MPI_Fetch_and_op), grain N/(100P) as §4.1.
//   static    static round robin over ranks (§3), no communication.
// Lists carry over between frames (§4.2.1): a rank's next list is what it processed this frame (rma, request).
//
// FRAME BOUNDARY AND TERMINATION. Two barriers a frame (start, done). Termination inside a frame uses the
// active count of core/active_workers.hpp (I-T): one integer in rank 0's window, updated with
// MPI_Fetch_and_op. That is not a master: rank 0 runs no code for it (passive target), it is only where the
// word lives; no rank decides for the others. A fully distributed detector (e.g. Dijkstra–Safra tokens) would
// remove the one hot word but costs a token round per idle period; the count is touched only at steals and
// list exhaustion, never per item. The request scheduler ends its frame with MPI_Ibarrier while still
// answering requests (empty), so no request is left unanswered across frames.
//
// AUDIT. Every frame: per-item execution counts reduced to rank 0 (MPI_Reduce); each must be 1; the frame's
// triangle count must equal a serial loop's. A failure prints "AUDIT FAILED" and every rank exits 1.
// Negative controls: --plant-defect skip-reread (the RMA thief drops T4/T5) with --force-overlap (the thief
// waits until the victim has claimed into the planned share before T3: the interleaving the defect gets
// wrong, forced), and --plant-defect request-keeps-share (the owner sends a share and keeps it).
//
// FAULTS. --stall R:F:MS sleeps rank R for MS ms after its first item of frame F (its work is stolen, the frame
// completes; request-based stealing must wait for it: the stalled owner answers no request). --die R:F ends
// rank R abruptly in frame F; mpirun then ends the job non-zero, and a per-rank watchdog (--watchdog-s) ends
// any rank that makes no progress (exit 86) in case the launcher does not.
#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/id_range.hpp"
#include "core/policies.hpp"
#include "core/synthetic_work.hpp"
#include "distributed/rma_stealing.hpp"
#include "distributed/rma_window.hpp"
#include "reporting/command_line.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif
#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif

namespace fs = frontsteal;
namespace fm = frontsteal::mpi;
namespace ts = frontsteal::tess;
namespace report = frontsteal::report;

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::string_view kProgram = "frontsteal-mpi";
constexpr int kWatchdogExitCode = 86;  // as core/watchdog.hpp: distinct from a failed audit (1) and usage (2)
constexpr int kTagRequest = 181;
constexpr int kTagReply = 182;

constexpr const char* kDescription = R"(usage: mpirun -np P frontsteal-mpi [options]

Runs the frame loop across MPI ranks under each scheduler (rma, request, central, static), audits every frame
(each item executed exactly once, triangle count equal to a serial loop's) and prints a table per scheduler:
frames/s, per-rank busy time, items, steals, mean steal latency, bytes moved, owner overhead per item.
As root, Open MPI needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 in the environment; with more
ranks than cores add --oversubscribe --mca mpi_yield_when_idle 1.)";
constexpr const char* kFooter = R"(
Exit status: 0 all audits passed; 1 an audit failed; 2 bad command line; 3 --die; 86 watchdog.)";

// Rank as the launcher tells it, before MPI_Init: only rank 0 prints usage errors.
int launcher_rank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    if (const char* s = std::getenv(v)) return std::atoi(s);
  }
  return 0;
}

std::vector<std::string> split(std::string_view s, char sep) {
  std::vector<std::string> out;
  while (true) {
    const auto p = s.find(sep);
    out.emplace_back(s.substr(0, p));
    if (p == std::string_view::npos) break;
    s.remove_prefix(p + 1);
  }
  return out;
}

// "A:B:C" of `parts` non-negative integers, each at most the matching bound.
CLI::Validator integers_validator(std::vector<int> bounds, std::string shape) {
  return CLI::Validator(
      [bounds, shape](std::string& text) -> std::string {
        const auto p = split(text, ':');
        if (p.size() != bounds.size()) return "expects " + shape + ", got '" + text + "'";
        for (std::size_t k = 0; k < p.size(); ++k) {
          int v = -1;
          const auto [end, ec] = std::from_chars(p[k].data(), p[k].data() + p[k].size(), v);
          if (ec != std::errc{} || end != p[k].data() + p[k].size() || v < 0 || v > bounds[k]) {
            return "expects " + shape + " (non-negative integers, at most " + std::to_string(bounds[k]) + " in place " +
                   std::to_string(k + 1) + "), got '" + text + "'";
          }
        }
        return {};
      },
      shape);
}

struct Options {
  std::string scene = "synthetic:20000";
  int frames = 30;
  std::vector<std::string> schedulers{"rma", "request", "central", "static"};
  std::uint32_t work_ns = 2000;
  std::uint32_t skew = 20;
  double tolerance = 1.0;
  std::string json;
  double watchdog_s = 60;
  int stall_rank = -1, stall_frame = -1, stall_ms = 0;
  int die_rank = -1, die_frame = -1;
  std::string defect = "none";
  bool force_overlap = false;
  bool calibrate = false;
  bool require_steals = false;
  std::string owner_fence = "cpu";
  bool quiet = false;
};

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(std::string(kProgram), kDescription, kFooter);
  cli.set_speaks(launcher_rank() == 0);  // every rank parses; rank 0 alone prints
  cli.option("--scene", o.scene, "synthetic:N | teapot | teacup | teaspoon | plant:N[:seed] | model file")
      ->check(CLI::Validator(
          [](std::string& v) -> std::string {
            if (v.empty()) return "needs a non-empty value";
            if (v.rfind("synthetic:", 0) != 0) return {};
            fs::ItemId n = 0;
            const std::string_view t = std::string_view(v).substr(10);
            const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), n);
            if (ec != std::errc{} || end != t.data() + t.size() || n < 1 || n > 50000000) {
              return "synthetic:N needs N between 1 and 50000000, got '" + v + "'";
            }
            return {};
          },
          ""));
  cli.option("--frames", o.frames, "frames along the camera path")->check(CLI::Range(1, 100000));
  cli.app().add_option("--schedulers", o.schedulers, "comma list of rma,request,central,static")
      ->delimiter(',')->check(CLI::IsMember({"rma", "request", "central", "static"}));
  cli.option("--work-ns", o.work_ns, "synthetic: cost of a light item in ~ns of busy work")->check(CLI::Range(0u, 100000000u));
  cli.option("--skew", o.skew, "synthetic: the heavy fifth of the ids (a window that moves each frame) costs K x")
      ->check(CLI::Range(1u, 10000u));
  cli.option("--tolerance", o.tolerance, "tessellation pixel tolerance")->check(CLI::PositiveNumber);
  cli.option("--json", o.json, "also write the results as JSON to this file");
  cli.option("--watchdog-s", o.watchdog_s, "a rank that makes no progress for S s exits 86 (0 = off)")
      ->check(CLI::Range(0.0, 86400.0));
  std::string stall, die;
  cli.option("--stall", stall, "R:F:MS: rank R sleeps MS ms after its first item of frame F (fault test)")
      ->check(integers_validator({1 << 20, 100000, 3600000}, "RANK:FRAME:MS"));
  cli.option("--die", die, "R:F: rank R exits abruptly (status 3) after its first item of frame F (fault test)")
      ->check(integers_validator({1 << 20, 100000}, "RANK:FRAME"));
  cli.option("--plant-defect", o.defect, "negative controls: none | skip-reread (rma thief skips T4/T5) | "
             "request-keeps-share (request owner sends a share and keeps it)")
      ->check(CLI::IsMember({"none", "skip-reread", "request-keeps-share"}));
  cli.flag("--force-overlap", o.force_overlap, "rma thieves wait, before T3, until the victim has claimed into the planned share");
  cli.option("--owner-fence", o.owner_fence, "the rma owner's F1: cpu (a seq_cst fence, no MPI call on the owner path) | "
             "win-sync (MPI_Win_sync + the fence: the standard's barrier, but a progress call per claim)")
      ->check(CLI::IsMember({"cpu", "win-sync"}));
  cli.flag("--require-steals", o.require_steals, "exit 1 unless rma and request each made at least one steal (tests: "
           "stealing was exercised)");
  cli.flag("--calibrate", o.calibrate, "measure get/put/CAS/fetch-and-op/flush latency and the owner's per-item "
           "costs, then exit");
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  if (!stall.empty()) {
    const auto p = split(stall, ':');
    o.stall_rank = std::stoi(p[0]), o.stall_frame = std::stoi(p[1]), o.stall_ms = std::stoi(p[2]);
  }
  if (!die.empty()) {
    const auto p = split(die, ':');
    o.die_rank = std::stoi(p[0]), o.die_frame = std::stoi(p[1]);
  }
  return o;
}

// ---- the workload: every rank builds the same one --------------------------------------------------------
struct Workload {
  fs::ItemId n = 0;
  std::string kind;
  std::function<std::uint32_t(int frame, fs::ItemId id)> run;  // executes item id of frame f; its triangles
  std::function<std::uint64_t(int frame)> serial_triangles;     // the serial loop's count for frame f (rank 0)
  // Tessellation state (empty for synthetic).
  ts::Model model;
  std::vector<ts::PreparedSurface> prepared;
  std::vector<ts::TriangleBuffers> buffers;
  std::vector<ts::Camera> cameras;
  std::vector<ts::Frustum> frusta;
  ts::TessellationSettings settings;
  ts::TessellationScratch scratch;
  std::vector<std::uint64_t> serial;
};

// Synthetic skewed cost: a fifth of the ids are `skew` times heavier, and that window moves with the frame so
// last frame's allocation is never quite right (the case stealing exists for).
bool heavy(int frame, fs::ItemId id, fs::ItemId n) {
  const std::uint64_t shifted = (std::uint64_t{id} + std::uint64_t(frame) * (n / 37 + 1)) % n;
  return shifted * 5 >= std::uint64_t{n} * 4;
}
std::uint32_t synthetic_triangles(int frame, fs::ItemId id) {
  return static_cast<std::uint32_t>((id * 2654435761u ^ static_cast<std::uint32_t>(frame) * 40503u) % 97u + 1u);
}

void build_workload(const Options& o, int rank, Workload& wl) {
  if (o.scene.rfind("synthetic:", 0) == 0) {
    wl.kind = "synthetic";
    wl.n = static_cast<fs::ItemId>(std::stoul(o.scene.substr(10)));  // checked by parse()
    const fs::ItemId n = wl.n;
    const std::uint32_t light = o.work_ns, heavy_cost = o.work_ns * o.skew;
    wl.run = [n, light, heavy_cost](int f, fs::ItemId id) {
      fs::spin_work(heavy(f, id, n) ? heavy_cost : light);
      return synthetic_triangles(f, id);
    };
    wl.serial_triangles = [n](int f) {
      std::uint64_t t = 0;
      for (fs::ItemId id = 0; id < n; ++id) t += synthetic_triangles(f, id);
      return t;
    };
    return;
  }
  wl.kind = "tessellation";
  wl.model = ts::load_scene(o.scene, FRONTSTEAL_DATA_DIR);
  wl.n = static_cast<fs::ItemId>(wl.model.surfaces.size());
  if (wl.n == 0) throw std::runtime_error("scene '" + o.scene + "' has no surfaces");
  for (const ts::Surface& s : wl.model.surfaces) wl.prepared.push_back(ts::prepare_surface(s));
  wl.buffers.resize(wl.n);
  wl.settings.pixel_tolerance = o.tolerance;
  const ts::Box box = ts::model_box(wl.model);
  for (int f = 0; f < o.frames; ++f) {
    wl.cameras.push_back(ts::camera_on_path(box, f, o.frames));
    wl.frusta.push_back(ts::Frustum::of(wl.cameras.back()));
  }
  wl.run = [&wl](int f, fs::ItemId id) {
    return ts::tessellate_surface(wl.prepared[id], wl.cameras[f], wl.frusta[f], wl.settings, wl.scratch,
                                  wl.buffers[id]).triangles;
  };
  if (rank == 0) {  // the serial reference: a plain loop, once, before any scheduler runs
    for (int f = 0; f < o.frames; ++f) {
      std::uint64_t t = 0;
      for (fs::ItemId id = 0; id < wl.n; ++id) t += wl.run(f, id);
      wl.serial.push_back(t);
    }
  }
  wl.serial_triangles = [&wl](int f) { return wl.serial[static_cast<std::size_t>(f)]; };
}

// ---- per rank, per scheduler: what was measured ------------------------------------------------------------
struct RankStats {
  double busy_s = 0;            // time inside item functions
  double items = 0;
  double steals = 0;            // successful steals (non-empty shares received)
  double steal_attempts = 0;    // try_steal calls / requests sent
  double steal_latency_s = 0;   // summed over successful steals
  double steal_latency_max_s = 0;
  double bytes = 0;             // RMA payload bytes issued + message bytes sent by this rank
  double owner_overhead_s = 0;  // owner-path protocol time (claims, polls), measured around the calls
  double owner_ops = 0;         // claims (rma) / polls (request)
  double requests_served = 0;
  double owner_overhead_median_ns = 0;  // median of the recorded owner-path samples (robust to preemption)
  double t4_wait_s = 0;                 // rma thief: time waiting at T4 for a victim's claim in flight
  double t4_spins = 0;
  double idle_s = 0;                    // time in the idle (stealing / requesting) loop, steals' work excluded
};
constexpr int kStatFields = sizeof(RankStats) / sizeof(double);

// Progress for the watchdog: the time of the last item or frame boundary on this rank.
std::atomic<std::int64_t> g_last_progress{0};
std::atomic<int> g_frame{-1};
std::atomic<const char*> g_phase{"start"};
std::atomic<bool> g_watchdog_armed{false};  // armed once the frames start (the serial reference may be long)
void progress() { g_last_progress.store(Clock::now().time_since_epoch().count(), std::memory_order_relaxed); }

struct Frame {
  int f;
  std::vector<std::uint32_t>* counts;
  std::uint64_t triangles = 0;
};

class Runner {
 public:
  Runner(const Options& o, Workload& wl, int rank, int ranks, fm::RmaWindow& win)
      : o_(o), wl_(wl), rank_(rank), ranks_(ranks), win_(win), active_(win) {
    for (int v = 0; v < ranks; ++v) {
      if (v != rank) victims_.push_back(v);
    }
    std::mt19937_64 rng(0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(rank + 1));
    std::shuffle(victims_.begin(), victims_.end(), rng);  // §4.2.1: victims in a random order per processor
    defects_ = o.defect == "skip-reread" ? fs::Defect::kSkipFrontReread : fs::Defect::kNone;
  }

  // Runs one item, with the fault hooks. Returns nothing; counts and triangles go to the frame.
  void execute(Frame& fr, fs::ItemId id) {
    const auto t0 = Clock::now();
    fr.triangles += wl_.run(fr.f, id);
    (*fr.counts)[id] += 1;
    stats_.busy_s += std::chrono::duration<double>(Clock::now() - t0).count();
    stats_.items += 1;
    progress();
    if (!first_item_done_) {
      first_item_done_ = true;
      if (fr.f == o_.die_frame && rank_ == o_.die_rank) {
        std::fprintf(stderr, "%s: rank %d: --die: exiting abruptly in frame %d\n", kProgram.data(), rank_, fr.f);
        std::fflush(stderr);
        std::_Exit(3);
      }
      if (fr.f == o_.stall_frame && rank_ == o_.stall_rank) stall(fr.f);
    }
  }

  void begin_frame(const std::string& scheduler) {
    first_item_done_ = false;
    scheduler_ = &scheduler;
  }

  // --stall: sleep MS ms between two items (never between O1 and O4). Under rma, also until a thief has
  // lowered this rank's End (its work was stolen while it stalled), bounded by 60 s: the steal is then a
  // fact the test can assert, not a matter of timing.
  void stall(int frame) {
    std::fprintf(stderr, "%s: rank %d: --stall: stalling %d ms in frame %d (%s)\n", kProgram.data(), rank_,
                 o_.stall_ms, frame, scheduler_->c_str());
    const auto start = Clock::now();
    const std::uint32_t end_before = win_.local_u32(fm::kEnd).load(std::memory_order_acquire);
    std::this_thread::sleep_for(std::chrono::milliseconds(o_.stall_ms));
    if (*scheduler_ == "rma") {
      while (win_.local_u32(fm::kEnd).load(std::memory_order_acquire) == end_before &&
             Clock::now() - start < std::chrono::seconds(60)) {
        win_.sync();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        progress();
      }
      const std::uint32_t end_after = win_.local_u32(fm::kEnd).load(std::memory_order_acquire);
      std::fprintf(stderr, "%s: rank %d: --stall: %s while stalled (End %u -> %u)\n", kProgram.data(), rank_,
                   end_after < end_before ? "work was stolen" : "NOTHING was stolen", end_before, end_after);
    }
    progress();
  }

  // ---- rma: load stealing over the window ----
  void rma_frame(Frame& fr, fm::RmaOwner& owner, fm::RmaThief& thief, fs::RangeList& log) {
    log.clear();
    drain_rma(fr, owner, log);
    active_.leave();  // A2: own list exhausted, every claimed item done
    fm::RmaStealHooks hooks;
    hooks.defects = defects_;
    hooks.force_overlap = o_.force_overlap;
    std::uint32_t failed_rounds = 0;
    const auto idle_start = Clock::now();
    const double busy_before = stats_.busy_s;
    while (!active_.all_idle()) {  // A3
      bool got = false;
      for (int v : victims_) {
        const auto t0 = Clock::now();
        stats_.steal_attempts += 1;
        const fm::RmaStealOutcome out = thief.try_steal(v, hooks);
        if (out != fm::RmaStealOutcome::kStolen) continue;
        const double lat = std::chrono::duration<double>(Clock::now() - t0).count();
        stats_.steals += 1;
        stats_.steal_latency_s += lat;
        stats_.steal_latency_max_s = std::max(stats_.steal_latency_max_s, lat);
        owner.install(thief.share());
        drain_rma(fr, owner, log);
        active_.leave();  // A2: the stolen share is done
        got = true;
        break;
      }
      // Back off after fruitless rounds (up to 256 us): with more ranks than cores an idle thief's polling
      // takes the CPU from the very owner it waits for.
      if (got) {
        failed_rounds = 0;
      } else if (++failed_rounds < 4) {
        std::this_thread::yield();
      } else {
        std::this_thread::sleep_for(std::chrono::microseconds(1u << std::min<std::uint32_t>(failed_rounds - 4, 8)));
      }
    }
    stats_.idle_s += std::chrono::duration<double>(Clock::now() - idle_start).count() - (stats_.busy_s - busy_before);
  }

  // ---- request: §7's request-based stealing with messages ----
  void request_frame(Frame& fr, fs::RangeList list, fs::RangeList& log) {
    log.clear();
    drain_request(fr, list, log);
    active_.leave();  // A2
    const auto idle_start = Clock::now();
    const double busy_before = stats_.busy_s;
    int outstanding = -1;
    std::uint32_t empty_replies = 0;
    std::size_t next_victim = 0;
    Clock::time_point sent_at{};
    while (true) {
      serve_requests(nullptr);
      if (outstanding < 0) {
        if (active_.all_idle()) break;  // A3
        if (victims_.empty()) continue;
        outstanding = victims_[next_victim++ % victims_.size()];
        const std::int32_t frame = fr.f;
        fm::check_mpi(MPI_Send(&frame, 1, MPI_INT32_T, outstanding, kTagRequest, MPI_COMM_WORLD), "MPI_Send");
        stats_.bytes += 4;
        stats_.steal_attempts += 1;
        sent_at = Clock::now();
        continue;
      }
      int flag = 0;
      MPI_Status st;
      fm::check_mpi(MPI_Iprobe(outstanding, kTagReply, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
      if (!flag) continue;
      int words = 0;
      MPI_Get_count(&st, MPI_UINT32_T, &words);
      std::vector<std::uint32_t> buf(static_cast<std::size_t>(words));
      fm::check_mpi(MPI_Recv(buf.data(), words, MPI_UINT32_T, outstanding, kTagReply, MPI_COMM_WORLD,
                             MPI_STATUS_IGNORE), "MPI_Recv");
      outstanding = -1;
      if (words == 0) {  // an empty answer: back off a little before asking the next victim (as rma's idle loop)
        if (++empty_replies >= 4) {
          std::this_thread::sleep_for(std::chrono::microseconds(1u << std::min<std::uint32_t>(empty_replies - 4, 8)));
        }
        continue;
      }
      empty_replies = 0;
      const double lat = std::chrono::duration<double>(Clock::now() - sent_at).count();
      stats_.steals += 1;
      stats_.steal_latency_s += lat;
      stats_.steal_latency_max_s = std::max(stats_.steal_latency_max_s, lat);
      fs::RangeList share;
      for (int i = 0; i + 1 < words; i += 2) share.push_back({buf[i], buf[i + 1]});
      drain_request(fr, std::move(share), log);
      active_.leave();  // A2 (the victim joined for us, A1, before it replied)
    }
    stats_.idle_s += std::chrono::duration<double>(Clock::now() - idle_start).count() - (stats_.busy_s - busy_before);
    // Frame end: every rank arrives with no outstanding request; answer stragglers until all have arrived.
    MPI_Request barrier;
    fm::check_mpi(MPI_Ibarrier(MPI_COMM_WORLD, &barrier), "MPI_Ibarrier");
    for (int done = 0; !done;) {
      serve_requests(nullptr);
      fm::check_mpi(MPI_Test(&barrier, &done, MPI_STATUS_IGNORE), "MPI_Test");
    }
  }

  // ---- central counter in rank 0's window ----
  void central_frame(Frame& fr) {
    const std::uint64_t grain = std::max<std::uint64_t>(1, wl_.n / (100ull * static_cast<std::uint64_t>(ranks_)));
    while (true) {
      const auto t0 = Clock::now();
      const std::uint64_t s = win_.fetch_add_u64(0, fm::kNextItem, grain);
      record_owner_op(Clock::now() - t0);
      if (s >= wl_.n) break;
      const std::uint64_t e = std::min<std::uint64_t>(s + grain, wl_.n);
      for (std::uint64_t id = s; id < e; ++id) execute(fr, static_cast<fs::ItemId>(id));
    }
  }

  // ---- static round robin ----
  void static_frame(Frame& fr) {
    for (std::uint64_t id = static_cast<std::uint64_t>(rank_); id < wl_.n; id += static_cast<std::uint64_t>(ranks_)) {
      execute(fr, static_cast<fs::ItemId>(id));
    }
  }

  RankStats& stats() {
    if (!owner_samples_.empty()) {
      auto mid = owner_samples_.begin() + static_cast<std::ptrdiff_t>(owner_samples_.size() / 2);
      std::nth_element(owner_samples_.begin(), mid, owner_samples_.end());
      stats_.owner_overhead_median_ns = *mid;
    }
    return stats_;
  }
  fm::RmaActiveCount& active() { return active_; }

 private:
  void drain_rma(Frame& fr, fm::RmaOwner& owner, fs::RangeList& log) {
    while (true) {
      const auto t0 = Clock::now();
      const std::optional<fs::ItemId> id = owner.try_claim();
      record_owner_op(Clock::now() - t0);
      if (!id) return;
      fs::append_merging(log, {*id, *id + 1});
      execute(fr, *id);
    }
  }

  // The request owner: its list is private; between items it polls for steal requests.
  void drain_request(Frame& fr, fs::RangeList list, fs::RangeList& log) {
    std::size_t i = 0;
    while (true) {
      serve_requests(&list, &i);
      while (i < list.size() && list[i].empty()) ++i;
      if (i >= list.size()) return;
      const fs::ItemId id = list[i].begin++;
      fs::append_merging(log, {id, id + 1});
      execute(fr, id);
    }
  }

  // Answers every pending steal request: with the second half of list[i..] when this rank is busy (list
  // given), with an empty reply otherwise. The poll's cost is what §7 says busy processors must pay.
  void serve_requests(fs::RangeList* list, std::size_t* index = nullptr) {
    while (true) {
      int flag = 0;
      MPI_Status st;
      const auto t0 = Clock::now();
      fm::check_mpi(MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
      if (list != nullptr) record_owner_op(Clock::now() - t0);
      if (!flag) return;
      std::int32_t frame = 0;
      fm::check_mpi(MPI_Recv(&frame, 1, MPI_INT32_T, st.MPI_SOURCE, kTagRequest, MPI_COMM_WORLD,
                             MPI_STATUS_IGNORE), "MPI_Recv");
      std::vector<std::uint32_t> reply;
      if (list != nullptr) {
        std::uint64_t remaining = 0;
        for (std::size_t k = *index; k < list->size(); ++k) remaining += (*list)[k].size();
        if (remaining >= 2) {  // keep the first half (items_left_to_victim), send the second
          std::uint64_t keep = fs::items_left_to_victim(remaining);
          fs::RangeList mine(list->begin(), list->begin() + static_cast<std::ptrdiff_t>(*index));
          for (std::size_t k = *index; k < list->size(); ++k) {
            fs::IdRange r = (*list)[k];
            if (keep >= r.size()) {
              keep -= r.size();
              mine.push_back(r);
              continue;
            }
            const fs::IdRange kept{r.begin, static_cast<fs::ItemId>(r.begin + keep)};
            const fs::IdRange sent{kept.end, r.end};
            keep = 0;
            if (!kept.empty()) mine.push_back(kept);
            if (!sent.empty()) reply.insert(reply.end(), {sent.begin, sent.end});
          }
          if (defects_keep_share()) {  // negative control: the share is sent and also kept
            mine = *list;
          }
          *list = std::move(mine);
        }
      }
      if (!reply.empty()) active_.join();  // A1 on the thief's behalf, before the share leaves (I-T)
      fm::check_mpi(MPI_Send(reply.data(), static_cast<int>(reply.size()), MPI_UINT32_T, st.MPI_SOURCE, kTagReply,
                             MPI_COMM_WORLD), "MPI_Send");
      stats_.bytes += 4.0 * static_cast<double>(reply.size());
      stats_.requests_served += 1;
    }
  }
  void record_owner_op(Clock::duration d) {
    const double ns = std::chrono::duration<double, std::nano>(d).count();
    stats_.owner_overhead_s += ns * 1e-9;
    stats_.owner_ops += 1;
    if (owner_samples_.size() < (1u << 21)) owner_samples_.push_back(static_cast<float>(ns));
  }
  bool defects_keep_share() const { return o_.defect == "request-keeps-share"; }

  const Options& o_;
  Workload& wl_;
  int rank_, ranks_;
  fm::RmaWindow& win_;
  fm::RmaActiveCount active_;
  std::vector<int> victims_;
  fs::Defect defects_ = fs::Defect::kNone;
  RankStats stats_;
  std::vector<float> owner_samples_;
  bool first_item_done_ = false;
  const std::string* scheduler_ = nullptr;
};

struct SchedulerResult {
  std::string name;
  std::vector<double> frame_s;           // rank 0's wall time per frame
  std::vector<RankStats> ranks;          // gathered on rank 0
  std::uint64_t audited_frames = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Runs every frame of one scheduler; returns false (after printing on rank 0) when an audit failed.
bool run_scheduler(const std::string& name, const Options& o, Workload& wl, int rank, int ranks,
                   fm::RmaWindow& win, SchedulerResult& result) {
  Runner runner(o, wl, rank, ranks, win);
  fm::RmaOwner owner(win, rank, o.owner_fence == "win-sync");
  fm::RmaThief thief(win, runner.active());
  std::vector<std::uint32_t> counts(wl.n), total(rank == 0 ? wl.n : 0);
  fs::RangeList list = fs::block_allocation(wl.n, static_cast<fs::WorkerId>(ranks))[static_cast<std::size_t>(rank)];
  fs::RangeList log;
  log.reserve(1024);
  const double bytes_before = static_cast<double>(win.bytes_moved());
  result.name = name;
  bool ok = true;
  for (int f = 0; f < o.frames && ok; ++f) {
    g_frame.store(f);
    g_phase.store("frame setup");
    std::fill(counts.begin(), counts.end(), 0u);
    // Between frames (every rank is past the previous frame's done barrier): install, re-arm, reset.
    if (name == "rma") owner.install(list);
    if (rank == 0) {
      runner.active().rearm(ranks);               // E4
      win.atomic_write_u64(0, fm::kNextItem, 0);  // central counter
    }
    win.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame start (E1/E2)
    g_phase.store("frame");
    progress();
    const auto t0 = Clock::now();
    Frame fr{f, &counts};
    runner.begin_frame(name);
    if (name == "rma") {
      runner.rma_frame(fr, owner, thief, log);
      list = log;
    } else if (name == "request") {
      runner.request_frame(fr, list, log);
      list = log;
    } else if (name == "central") {
      runner.central_frame(fr);
    } else {
      runner.static_frame(fr);
    }
    g_phase.store("frame done barrier");
    win.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame done (E3/E6)
    progress();
    result.frame_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    // The audit: counts and triangles reduced to rank 0, the verdict broadcast.
    g_phase.store("audit");
    MPI_Reduce(counts.data(), total.data(), static_cast<int>(wl.n), MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD);
    std::uint64_t tri = 0;
    MPI_Reduce(&fr.triangles, &tri, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    int verdict = 1;
    if (rank == 0) {
      std::uint64_t wrong = 0;
      fs::ItemId first = 0;
      for (fs::ItemId id = 0; id < wl.n; ++id) {
        if (total[id] != 1) {
          if (wrong++ == 0) first = id;
        }
      }
      const std::uint64_t serial = wl.serial_triangles(f);
      if (wrong > 0) {
        std::fprintf(stderr, "%s: AUDIT FAILED: scheduler %s, frame %d: item %u executed %u times (%llu items not "
                     "executed exactly once)\n", kProgram.data(), name.c_str(), f, first, total[first],
                     static_cast<unsigned long long>(wrong));
        verdict = 0;
      } else if (tri != serial) {
        std::fprintf(stderr, "%s: AUDIT FAILED: scheduler %s, frame %d: %llu triangles, the serial loop made %llu\n",
                     kProgram.data(), name.c_str(), f, static_cast<unsigned long long>(tri),
                     static_cast<unsigned long long>(serial));
        verdict = 0;
      }
      if (verdict) ++result.audited_frames;
      if (!o.quiet && (f + 1) % 10 == 0) {
        std::fprintf(stderr, "%s: %s: frame %d/%d audited (exactly once, %llu triangles)\n", kProgram.data(),
                     name.c_str(), f + 1, o.frames, static_cast<unsigned long long>(tri));
      }
    }
    MPI_Bcast(&verdict, 1, MPI_INT, 0, MPI_COMM_WORLD);
    ok = verdict == 1;
  }
  runner.stats().bytes += static_cast<double>(win.bytes_moved()) - bytes_before;
  runner.stats().t4_wait_s = thief.t4_wait_s();
  runner.stats().t4_spins = static_cast<double>(thief.t4_spins());
  result.ranks.resize(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(&runner.stats(), kStatFields, MPI_DOUBLE, rank == 0 ? result.ranks.data() : nullptr, kStatFields,
             MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return ok;
}

void start_watchdog(double limit_s, int rank) {
  if (limit_s <= 0) return;
  progress();
  std::thread([limit_s, rank] {
    while (true) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!g_watchdog_armed.load(std::memory_order_relaxed)) continue;
      const auto last = Clock::time_point(Clock::duration(g_last_progress.load(std::memory_order_relaxed)));
      const double idle = std::chrono::duration<double>(Clock::now() - last).count();
      if (idle > limit_s) {
        std::fprintf(stderr, "%s: rank %d: WATCHDOG: no progress for %.1f s (frame %d, %s): a rank died or "
                     "hangs; exiting %d instead of hanging\n", kProgram.data(), rank, idle, g_frame.load(),
                     g_phase.load(), kWatchdogExitCode);
        std::fflush(stderr);
        std::_Exit(kWatchdogExitCode);
      }
    }
  }).detach();
}

// ---- calibration: one-sided latencies and the owner's per-item costs ----------------------------------------
int calibrate(int rank, int ranks, fm::RmaWindow& win) {
  if (ranks < 2) {
    if (rank == 0) std::fprintf(stderr, "%s: --calibrate needs at least 2 ranks\n", kProgram.data());
    return 2;
  }
  constexpr int kReps = 20000;
  std::vector<std::pair<std::string, double>> rows;
  auto time_op = [&](const char* what, auto&& op) {
    std::vector<double> ns;
    ns.reserve(kReps);
    for (int i = 0; i < kReps; ++i) {
      const auto t0 = Clock::now();
      op();
      ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
    }
    rows.emplace_back(what, median(ns));
  };
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    time_op("MPI_Get 4 B + MPI_Win_flush (remote)", [&] { (void)win.get_u32(1, fm::kFront); });
    time_op("MPI_Put 4 B + MPI_Win_flush (remote)", [&] { win.put_u32(1, fm::kEntryCount, 0); });
    time_op("MPI_Compare_and_swap + flush (remote)", [&] { (void)win.cas_u32(1, fm::kLock, 7, 7); });
    time_op("MPI_Fetch_and_op SUM + flush (remote)", [&] { (void)win.fetch_add_i32(1, fm::kActive, 0); });
    time_op("MPI_Win_flush alone (nothing pending)", [&] { win.flush(1); });
    time_op("MPI_Win_sync (owner F1)", [&] { win.sync(); });
    fm::RmaActiveCount active(win);
    fm::RmaOwner owner(win, 0);
    fs::RangeList big{{0, static_cast<fs::ItemId>(std::min<std::uint32_t>(win.capacity(), 1u << 20))}};
    owner.install(big);
    time_op("RMA owner claim, F1 = MPI_Win_sync + fence", [&] { (void)owner.try_claim(); });
    fm::RmaOwner plain_owner(win, 0, false);
    plain_owner.install(big);
    time_op("RMA owner claim, F1 = fence only (default)", [&] { (void)plain_owner.try_claim(); });
    time_op("request owner poll (MPI_Iprobe, nothing pending)", [&] {
      int flag = 0;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagRequest, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
    });
    time_op("clock pair alone (measurement floor)", [] {});
    std::printf("calibration: rank 0 -> rank 1, %d repetitions each, median ns (measured, this machine)\n", kReps);
    for (const auto& [what, v] : rows) std::printf("  %-52s %10.0f ns\n", what.c_str(), v);
    std::printf("published reference (one computer, async progress): get ~1300 ns, CAS ~1700 ns\n");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return 0;
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);  // before MPI_Init: a bad flag costs no MPI start-up
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  start_watchdog(o.watchdog_s, rank);

  int status = 0;
  try {
    Workload wl;
    const auto load0 = Clock::now();
    build_workload(o, rank, wl);
    progress();
    fm::RmaWindow win(MPI_COMM_WORLD, std::max<std::uint32_t>(wl.n, 1));
    if (!win.unified()) {
      if (rank == 0) std::fprintf(stderr, "%s: the window's memory model is not MPI_WIN_UNIFIED: the owner's local "
                                  "loads and stores would not be coherent with thieves' RMA; refusing to run\n",
                                  kProgram.data());
      MPI_Finalize();
      return 1;
    }
    if (o.calibrate) {
      status = calibrate(rank, ranks, win);
    } else {
      if (rank == 0 && !o.quiet) {
        std::fprintf(stderr, "%s: %d ranks, scene %s (%s, %u items), %d frames; prepared in %.2f s\n",
                     kProgram.data(), ranks, o.scene.c_str(), wl.kind.c_str(), wl.n, o.frames,
                     std::chrono::duration<double>(Clock::now() - load0).count());
      }
      std::vector<SchedulerResult> results;
      progress();
      g_watchdog_armed.store(true);
      for (const std::string& s : o.schedulers) {
        results.emplace_back();
        if (!run_scheduler(s, o, wl, rank, ranks, win, results.back())) {
          status = 1;
          break;
        }
      }
      if (rank == 0 && status == 0 && o.require_steals) {
        for (const SchedulerResult& r : results) {
          double steals = 0;
          for (const RankStats& s : r.ranks) steals += s.steals;
          if ((r.name == "rma" || r.name == "request") && steals == 0) {
            std::fprintf(stderr, "%s: --require-steals: scheduler %s made no steal in %d frames\n", kProgram.data(),
                         r.name.c_str(), o.frames);
            status = 1;
          }
        }
      }
      MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
      if (rank == 0 && status == 0) {
        std::printf("\nfrontsteal-mpi: %d ranks, %s (%u items), %d frames, commit %s (measured)\n", ranks,
                    o.scene.c_str(), wl.n, o.frames, FRONTSTEAL_GIT_COMMIT);
        std::printf("%-8s %9s %11s | %4s %8s %9s %7s %7s %12s %11s %12s\n", "sched", "frames/s", "median ms",
                    "rank", "busy s", "items", "steals", "tries", "lat mean us", "bytes", "owner ns/op");
        std::printf("%-8s %9s %11s | %4s %8s %9s %7s %7s %12s %11s %12s\n", "", "", "(max ms)", "", "", "", "", "",
                    "", "", "(median)");
        for (const SchedulerResult& r : results) {
          double total = 0;
          for (double x : r.frame_s) total += x;
          for (std::size_t k = 0; k < r.ranks.size(); ++k) {
            const RankStats& s = r.ranks[k];
            std::printf("%-8s %9s %11s | %4zu %8.3f %9.0f %7.0f %7.0f %12.1f %11.0f %12.1f\n",
                        k == 0 ? r.name.c_str() : "",
                        k == 0 ? std::to_string(static_cast<double>(r.frame_s.size()) / total).substr(0, 8).c_str() : "",
                        k == 0 ? std::to_string(1000 * median(r.frame_s)).substr(0, 8).c_str()
                               : k == 1 ? ("(" + std::to_string(1000 * *std::max_element(r.frame_s.begin(),
                                                                                       r.frame_s.end())).substr(0, 7) + ")").c_str()
                                        : "",
                        k, s.busy_s, s.items, s.steals, s.steal_attempts,
                        s.steals > 0 ? 1e6 * s.steal_latency_s / s.steals : 0.0, s.bytes, s.owner_overhead_median_ns);
          }
        }
        std::printf("every frame audited: each item exactly once, triangles equal to the serial loop's\n");
        if (!o.json.empty()) {
          std::ofstream js(o.json);
          js << "{\n  \"program\": \"frontsteal-mpi\",\n  \"commit\": \"" << FRONTSTEAL_GIT_COMMIT
             << "\",\n  \"measured\": true,\n  \"ranks\": " << ranks << ",\n  \"scene\": \"" << json_escape(o.scene)
             << "\",\n  \"items\": " << wl.n << ",\n  \"frames\": " << o.frames << ",\n  \"schedulers\": [\n";
          for (std::size_t i = 0; i < results.size(); ++i) {
            const SchedulerResult& r = results[i];
            double total = 0;
            for (double x : r.frame_s) total += x;
            js << "    {\"name\": \"" << r.name << "\", \"frames_per_s\": " << r.frame_s.size() / total
               << ", \"median_frame_ms\": " << 1000 * median(r.frame_s)
               << ", \"max_frame_ms\": " << 1000 * *std::max_element(r.frame_s.begin(), r.frame_s.end()) << ", \"audited_frames\": "
               << r.audited_frames << ", \"per_rank\": [";
            for (std::size_t k = 0; k < r.ranks.size(); ++k) {
              const RankStats& s = r.ranks[k];
              js << (k ? ", " : "") << "{\"rank\": " << k << ", \"busy_s\": " << s.busy_s << ", \"items\": "
                 << s.items << ", \"steals\": " << s.steals << ", \"steal_attempts\": " << s.steal_attempts
                 << ", \"steal_latency_mean_us\": " << (s.steals > 0 ? 1e6 * s.steal_latency_s / s.steals : 0.0)
                 << ", \"steal_latency_max_us\": " << 1e6 * s.steal_latency_max_s << ", \"bytes_moved\": "
                 << s.bytes << ", \"owner_overhead_ns_per_op\": "
                 << (s.owner_ops > 0 ? 1e9 * s.owner_overhead_s / s.owner_ops : 0.0)
                 << ", \"owner_overhead_median_ns\": " << s.owner_overhead_median_ns << ", \"t4_wait_s\": "
                 << s.t4_wait_s << ", \"t4_polls\": " << s.t4_spins << ", \"idle_s\": " << s.idle_s << ", \"owner_ops\": "
                 << s.owner_ops << ", \"requests_served\": " << s.requests_served << "}";
            }
            js << "]}" << (i + 1 < results.size() ? "," : "") << "\n";
          }
          js << "  ]\n}\n";
          std::fprintf(stderr, "%s: wrote %s\n", kProgram.data(), o.json.c_str());
        }
      }
    }
    MPI_Barrier(MPI_COMM_WORLD);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: rank %d: %s\n", kProgram.data(), rank, e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
