// frame_runner.cpp — FrameRunner (frame_runner.hpp): items and faults, the rma, central and static frames,
// and the rank's statistics. The request scheduler's frame is in request_frame.cpp.
#include "distributed/frame_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

#include "distributed/idle_backoff.hpp"
#include "distributed/rank_ledger.hpp"
#include "distributed/rank_watchdog.hpp"
#include "measure/paired_comparison.hpp"

namespace frontsteal::mpi {

FrameRunner::FrameRunner(const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win, double owner_progress_us)
    : o_(o),
      wl_(wl),
      rank_(rank),
      ranks_(ranks),
      win_(win),
      protocol_(
          make_window_protocol(win, ranks, o.owner_fence == "win-sync",
                               o.defect == "skip-reread" ? WindowPolicy::kBrokenSkipsReread : WindowPolicy::kFenced)),
      progress_(MPI_COMM_WORLD, owner_progress_us),
      request_poll_(std::max(0.0, owner_progress_us)) {
  for (int v = 0; v < ranks; ++v) {
    if (v != rank) victims_.push_back(v);
  }
  std::mt19937_64 rng(0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(rank + 1));
  std::shuffle(victims_.begin(), victims_.end(), rng);  // §4.2.1: victims in a random order per processor
}

// Runs one item, with the fault hooks; counts and triangles go to the frame.
void FrameRunner::execute(Frame& fr, ItemId id) {
  const auto t0 = Clock::now();
  fr.triangles += wl_.run(fr.f, id);
  (*fr.counts)[id] += 1;
  ledger_mark(id);
  const double took = std::chrono::duration<double>(Clock::now() - t0).count();
  stats_.busy_s += took;
  if (!item_costs_.empty()) item_costs_[id] = static_cast<float>(took);
  stats_.items += 1;
  note_progress();
  if (first_item_done_) return;
  first_item_done_ = true;
  first_item_faults(fr.f);
}

void FrameRunner::first_item_faults(int frame) {
  if (frame == o_.die_frame && rank_ == o_.die_rank) {
    std::fprintf(stderr, "%s: rank %d: --die: exiting abruptly in frame %d\n", kProgram.data(), rank_, frame);
    std::fflush(stderr);
    std::_Exit(3);
  }
  if (frame == o_.stall_frame && rank_ == o_.stall_rank) stall(frame);
  if (frame == o_.slow_frame && rank_ == o_.slow_rank) start_slowdown(frame);
}

// --slow: this rank keeps running its items, stopped by the OS 9 ms of every 10 for slow_ms (os_slowdown.hpp).
void FrameRunner::start_slowdown(int frame) {
  std::fprintf(stderr, "%s: rank %d: --slow: slowed 10x by SIGSTOP/SIGCONT for %d ms from frame %d (%s)\n",
               kProgram.data(), rank_, o_.slow_ms, frame, scheduler_->c_str());
  if (runs_window_protocol(*scheduler_)) slow_end_before_ = win_.local(kEnd).load(std::memory_order_acquire);
  slowdown_.start(std::chrono::milliseconds(o_.slow_ms), 10);
}

// Under rma, once this rank's own list ran out in the slowed frame: did thieves lower its End meanwhile?
void FrameRunner::report_slowdown() {
  if (slow_end_before_ < 0) return;
  const std::uint32_t end_after = win_.local(kEnd).load(std::memory_order_acquire);
  std::fprintf(stderr, "%s: rank %d: --slow: %s while slowed (End %lld -> %u)\n", kProgram.data(), rank_,
               end_after < slow_end_before_ ? "work was stolen" : "NOTHING was stolen",
               static_cast<long long>(slow_end_before_), end_after);
  slow_end_before_ = -1;
}

void FrameRunner::begin_frame(const std::string& scheduler) {
  first_item_done_ = false;
  scheduler_ = &scheduler;
  if (scheduler == "rma-seeded" && item_costs_.size() != wl_.n) item_costs_.assign(wl_.n, 0.0f);
}

// --stall: sleep MS ms between two items (never between O1 and O4). Under rma, also until a thief has
// lowered this rank's End (its work was stolen while it stalled), bounded by 60 s: the steal is then a
// fact the test can assert, not a matter of timing. The MPI_Win_sync every millisecond is the stalled
// rank's progress call (owner_progress.hpp): a sleeping process makes none otherwise.
void FrameRunner::stall(int frame) {
  std::fprintf(stderr, "%s: rank %d: --stall: stalling %d ms in frame %d (%s)\n", kProgram.data(), rank_, o_.stall_ms,
               frame, scheduler_->c_str());
  const auto start = Clock::now();
  const std::uint32_t end_before = win_.local(kEnd).load(std::memory_order_acquire);
  std::this_thread::sleep_for(std::chrono::milliseconds(o_.stall_ms));
  if (runs_window_protocol(*scheduler_)) {
    while (win_.local(kEnd).load(std::memory_order_acquire) == end_before &&
           Clock::now() - start < std::chrono::seconds(60)) {
      win_.sync();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      note_progress();
    }
    const std::uint32_t end_after = win_.local(kEnd).load(std::memory_order_acquire);
    std::fprintf(stderr, "%s: rank %d: --stall: %s while stalled (End %u -> %u)\n", kProgram.data(), rank_,
                 end_after < end_before ? "work was stolen" : "NOTHING was stolen", end_before, end_after);
  }
  note_progress();
}

// ---- rma: load stealing over the window ----
void FrameRunner::rma_frame(Frame& fr, RangeList& log) {
  log.clear();
  drain_rma(fr, log);
  report_slowdown();
  protocol_->leave();  // A2: own list exhausted, every claimed item done
  StealHooks hooks;
  hooks.force_overlap = o_.force_overlap;
  std::uint32_t failed_rounds = 0;
  const auto idle_start = Clock::now();
  const double busy_before = stats_.busy_s;
  while (!protocol_->all_idle()) {  // A3
    bool got = false;
    for (int v : victims_) {
      const auto t0 = Clock::now();
      stats_.steal_attempts += 1;
      if (protocol_->try_steal(v, hooks) != StealOutcome::kStolen) continue;
      record_steal(Clock::now() - t0);
      protocol_->install(protocol_->share());
      drain_rma(fr, log);
      protocol_->leave();  // A2: the stolen share is done
      got = true;
      break;
    }
    // Back off after fruitless rounds (up to 256 us): with more ranks than cores an idle thief's polling
    // takes the CPU from the very owner it waits for.
    if (got) {
      failed_rounds = 0;
    } else {
      idle_back_off(++failed_rounds);
    }
  }
  stats_.idle_s += std::chrono::duration<double>(Clock::now() - idle_start).count() - (stats_.busy_s - busy_before);
}

// The owner's loop: claim (O1-O4), then maybe one progress call for the transport; both are owner overhead.
void FrameRunner::drain_rma(Frame& fr, RangeList& log) {
  while (true) {
    const auto t0 = Clock::now();
    const std::optional<ItemId> id = protocol_->try_claim();
    if (id && progress_.maybe_call(t0)) stats_.progress_calls += 1;
    record_owner_op(Clock::now() - t0);
    if (!id) return;
    append_merging(log, {*id, *id + 1});
    execute(fr, *id);
  }
}

// ---- central counter in rank 0's window ----
void FrameRunner::central_frame(Frame& fr) {
  const std::uint64_t grain = std::max<std::uint64_t>(1, wl_.n / (100ull * static_cast<std::uint64_t>(ranks_)));
  while (true) {
    const auto t0 = Clock::now();
    const std::uint64_t s = win_.fetch_and_op(0, kNextItem, grain, MPI_SUM);
    record_owner_op(Clock::now() - t0);
    if (s >= wl_.n) break;
    const std::uint64_t e = std::min<std::uint64_t>(s + grain, wl_.n);
    for (std::uint64_t id = s; id < e; ++id) {
      execute(fr, static_cast<ItemId>(id));
      // Rank 0 is the counter's home: where the transport needs the target's progress (owner_progress.hpp),
      // every other rank's fetch-and-op waits for rank 0's next call into MPI.
      if (rank_ == 0 && progress_.enabled() && progress_.maybe_call(Clock::now())) stats_.progress_calls += 1;
    }
  }
}

// ---- static by space: this rank's contiguous block of ids (a cluster renderer's screen or object region) ----
void FrameRunner::static_space_frame(Frame& fr) {
  const RangeList mine = block_allocation(wl_.n, static_cast<WorkerId>(ranks_))[static_cast<std::size_t>(rank_)];
  for (const IdRange& r : mine) {
    for (ItemId id = r.begin; id < r.end; ++id) execute(fr, id);
  }
}

// ---- static round robin ----
void FrameRunner::static_frame(Frame& fr) {
  for (std::uint64_t id = static_cast<std::uint64_t>(rank_); id < wl_.n; id += static_cast<std::uint64_t>(ranks_)) {
    execute(fr, static_cast<ItemId>(id));
  }
}

void FrameRunner::record_owner_op(Clock::duration d) {
  const double ns = std::chrono::duration<double, std::nano>(d).count();
  stats_.owner_overhead_s += ns * 1e-9;
  stats_.owner_ops += 1;
  if (owner_samples_.size() < (1u << 21)) owner_samples_.push_back(static_cast<float>(ns));
}

void FrameRunner::record_steal(Clock::duration d) {
  const double s = std::chrono::duration<double>(d).count();
  stats_.steals += 1;
  stats_.steal_latency_s += s;
  stats_.steal_latency_max_s = std::max(stats_.steal_latency_max_s, s);
  steal_latencies_us_.push_back(1e6 * s);
}

// At most this many samples enter a bootstrap (10,000 resamples each): an evenly strided subsample, so the
// interval is that of the subsample's median (with ~10^6 samples it would be far narrower still).
constexpr std::size_t kBootstrapSampleCap = 500;

template <class Sample>
stats::Interval strided_median_ci(const std::vector<Sample>& samples) {
  const std::size_t stride = samples.size() / kBootstrapSampleCap + 1;
  std::vector<double> sub;
  for (std::size_t i = 0; i < samples.size(); i += stride) sub.push_back(samples[i]);
  return stats::bootstrap_median_ci(sub);
}

void FrameRunner::absorb(const RankStats& extra, const std::vector<double>& steal_latencies_us) {
  stats_.busy_s += extra.busy_s;
  stats_.items += extra.items;
  stats_.steals += extra.steals;
  stats_.steal_attempts += extra.steal_attempts;
  stats_.steal_latency_s += extra.steal_latency_s;
  stats_.steal_latency_max_s = std::max(stats_.steal_latency_max_s, extra.steal_latency_max_s);
  stats_.idle_s += extra.idle_s;
  stats_.local_steals += extra.local_steals;
  stats_.progress_calls += extra.progress_calls;
  steal_latencies_us_.insert(steal_latencies_us_.end(), steal_latencies_us.begin(), steal_latencies_us.end());
}

RankStats& FrameRunner::finish_stats() {
  if (!owner_samples_.empty()) {
    std::vector<float> sorted = owner_samples_;
    auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), mid, sorted.end());
    stats_.owner_overhead_median_ns = *mid;
    const stats::Interval ci = strided_median_ci(owner_samples_);
    stats_.owner_overhead_ci_low_ns = ci.low;
    stats_.owner_overhead_ci_high_ns = ci.high;
  }
  if (!steal_latencies_us_.empty()) {
    const stats::Interval ci = strided_median_ci(steal_latencies_us_);
    stats_.steal_latency_median_us = ci.median;
    stats_.steal_latency_ci_low_us = ci.low;
    stats_.steal_latency_ci_high_us = ci.high;
  }
  return stats_;
}

}  // namespace frontsteal::mpi
