// scheduler_run.cpp — one scheduler's frames and their audit (scheduler_run.hpp).
#include "distributed/scheduler_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>

#include "distributed/cost_seeded_lists.hpp"
#include "distributed/frame_runner.hpp"
#include "distributed/hierarchical_rank.hpp"
#include "distributed/noise_window.hpp"
#include "distributed/rank_ledger.hpp"
#include "distributed/rank_watchdog.hpp"

namespace frontsteal::mpi {
namespace {

using Clock = std::chrono::steady_clock;

// Rank 0's verdict on one frame: every item exactly once, and the serial loop's triangle count.
bool audit_frame(const std::string& name, const Workload& wl, int f, const std::vector<std::uint32_t>& total,
                 std::uint64_t triangles) {
  std::uint64_t wrong = 0;
  ItemId first = 0;
  for (ItemId id = 0; id < wl.n; ++id) {
    if (total[id] != 1 && wrong++ == 0) first = id;
  }
  if (wrong > 0) {
    std::fprintf(stderr,
                 "%s: AUDIT FAILED: scheduler %s, frame %d: item %u executed %u times (%llu items not "
                 "executed exactly once)\n",
                 kProgram.data(), name.c_str(), f, first, total[first], static_cast<unsigned long long>(wrong));
    return false;
  }
  const std::uint64_t serial = wl.serial_triangles(f);
  if (triangles != serial) {
    std::fprintf(stderr, "%s: AUDIT FAILED: scheduler %s, frame %d: %llu triangles, the serial loop made %llu\n",
                 kProgram.data(), name.c_str(), f, static_cast<unsigned long long>(triangles),
                 static_cast<unsigned long long>(serial));
    return false;
  }
  return true;
}

}  // namespace

SchedulerRun::SchedulerRun(std::string name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                           double owner_progress_us)
    : name_(std::move(name)),
      o_(o),
      wl_(wl),
      rank_(rank),
      ranks_(ranks),
      win_(win),
      runner_(std::make_unique<FrameRunner>(o, wl, rank, ranks, win, owner_progress_us)),
      counts_(wl.n),
      total_(rank == 0 ? wl.n : 0),
      bytes_before_(static_cast<double>(win.bytes_moved())),
      noise_(std::make_unique<NoiseWindow>()) {
  if (rank == 0 && runs_window_protocol(name_)) {  // always: which code ran is part of every result
    std::fprintf(stderr, "%s: rma: core/stealing_protocol.hpp over the %s backend, policy %s\n", kProgram.data(),
                 runner_->protocol().backend_name().data(), runner_->protocol().policy_name().data());
  }
  if (name_ == "hier" || name_ == "hier-seeded") {
    FrameRunner* runner = runner_.get();
    HierFaultHooks faults{[runner](int frame) { runner->first_item_faults(frame); },
                          [runner] { runner->report_slowdown(); }};
    if (o.lifelines) {
      lifelines_ = std::make_unique<Lifelines>(win, rank, ranks, o.defect == "lifeline-drops-notice");
    }
    hier_ = std::make_unique<HierarchicalRank>(o, wl, rank, runner_->protocol(), runner_->victims(), owner_progress_us,
                                               lifelines_.get(), std::move(faults));
  }
  noise_->start();
}

SchedulerRun::~SchedulerRun() = default;

bool SchedulerRun::run_pass(int frames, double planted_s, std::vector<double>& frame_s) {
  const bool rma = runs_window_protocol(name_);
  FrameRunner& runner = *runner_;
  RangeList list = block_allocation(wl_.n, static_cast<WorkerId>(ranks_))[static_cast<std::size_t>(rank_)];
  RangeList log;
  log.reserve(1024);
  costs_before_.clear();  // a pass starts from blocks: its first prediction has one frame of times
  bool ok = true;
  for (int f = 0; f < frames && ok; ++f) {
    set_frame(f);
    ledger_begin_frame(f, name_);
    set_phase("frame setup");
    std::fill(counts_.begin(), counts_.end(), 0u);
    // Between frames (every rank is past the previous frame's done barrier): install, re-arm, reset.
    if (rma) runner.protocol().install(list);
    if (lifelines_) lifelines_->reset_for_next_frame();  // no other rank writes them now (lifelines.hpp, L3)
    if (rank_ == 0) {
      runner.protocol().rearm(static_cast<std::uint32_t>(ranks_));  // E4
      win_.accumulate_replace(0, kNextItem, std::uint64_t{0});      // central counter
    }
    win_.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame start (E1/E2)
    set_phase("frame");
    note_progress();
    const auto t0 = Clock::now();
    Frame fr{f, &counts_};
    runner.begin_frame(name_);
    if (hier_) {
      hier_->run_frame(f, counts_, fr.triangles, log);
      list = log;
    } else if (rma) {
      runner.rma_frame(fr, log);
      list = log;
    } else if (name_ == "request") {
      runner.request_frame(fr, list, log);
      list = log;
    } else if (name_ == "central") {
      runner.central_frame(fr);
    } else if (name_ == "static-space") {
      runner.static_space_frame(fr);
    } else {
      runner.static_frame(fr);
    }
    set_phase("frame done barrier");
    win_.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame done (E3/E6)
    ledger_frame_done();
    note_progress();
    // rma-seeded, hier-seeded: the next lists are contiguous blocks of equal predicted cost, each run heaviest
    // first (cost_seeded_lists.hpp), from every rank's item times of this frame and the one before; the
    // all-reduce is part of this frame's time.
    if (name_ == "rma-seeded" || name_ == "hier-seeded") {
      std::vector<float>& mine = hier_ ? hier_->item_costs() : runner.item_costs();
      std::vector<float> all(mine.size());
      MPI_Allreduce(mine.data(), all.data(), static_cast<int>(mine.size()), MPI_FLOAT, MPI_SUM, MPI_COMM_WORLD);
      const std::vector<float> predicted = predicted_costs(all, costs_before_);
      list = heavy_first(
          cost_balanced_blocks(predicted, static_cast<WorkerId>(ranks_))[static_cast<std::size_t>(rank_)], predicted);
      std::fill(mine.begin(), mine.end(), 0.0f);
      if (hier_) hier_->use_costs(predicted);  // the refills of the next frame priced with the prediction
      costs_before_ = std::move(all);
    }
    if (rank_ == 0 && planted_s > 0) {  // the planted slowdown: a busy wait by the clock, inside the timed region
      const auto until =
          Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(planted_s));
      while (Clock::now() < until) {
      }
    }
    frame_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    // The audit: counts and triangles reduced to rank 0, the verdict broadcast.
    set_phase("audit");
    MPI_Reduce(counts_.data(), total_.data(), static_cast<int>(wl_.n), MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD);
    std::uint64_t tri = 0;
    MPI_Reduce(&fr.triangles, &tri, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    int verdict = 1;
    if (rank_ == 0) {
      verdict = audit_frame(name_, wl_, f, total_, tri) ? 1 : 0;
      if (verdict) ++audited_frames_;
      if (!o_.quiet && o_.rounds == 0 && (f + 1) % 10 == 0) {
        std::fprintf(stderr, "%s: %s: frame %d/%d audited (exactly once, %llu triangles)\n", kProgram.data(),
                     name_.c_str(), f + 1, frames, static_cast<unsigned long long>(tri));
      }
    }
    MPI_Bcast(&verdict, 1, MPI_INT, 0, MPI_COMM_WORLD);
    ok = verdict == 1;
  }
  return ok;
}

void SchedulerRun::finish(SchedulerResult& result) {
  result.name = name_;
  result.audited_frames = audited_frames_;
  result.noise = noise_->finish();
  if (hier_) {
    RankStats extra;
    hier_->add_stats(extra);
    runner_->absorb(extra, hier_->steal_latencies_us());
  }
  RankStats& stats = runner_->finish_stats();
  stats.bytes += static_cast<double>(win_.bytes_moved()) - bytes_before_;
  stats.t4_wait_s = runner_->protocol().t4_wait_s();
  stats.t4_spins = static_cast<double>(runner_->protocol().t4_polls());
  stats.steal_operations = static_cast<double>(runner_->protocol().stolen_operations());
  result.ranks.resize(rank_ == 0 ? static_cast<std::size_t>(ranks_) : 0);
  MPI_Gather(&stats, kRankStatFields, MPI_DOUBLE, rank_ == 0 ? result.ranks.data() : nullptr, kRankStatFields,
             MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

bool run_scheduler(const std::string& name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                   double owner_progress_us, SchedulerResult& result) {
  SchedulerRun run(name, o, wl, rank, ranks, win, owner_progress_us);
  const bool ok = run.run_pass(o.frames, 0.0, result.frame_s);
  run.finish(result);
  return ok;
}

}  // namespace frontsteal::mpi
