// scheduler_run.cpp — one scheduler's frames and their audit (scheduler_run.hpp).
#include "distributed/scheduler_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "distributed/cost_seeded_lists.hpp"
#include "distributed/frame_runner.hpp"
#include "distributed/noise_window.hpp"
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

bool run_scheduler(const std::string& name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                   double owner_progress_us, SchedulerResult& result) {
  FrameRunner runner(o, wl, rank, ranks, win, owner_progress_us);
  const bool rma = runs_window_protocol(name);
  if (rank == 0 && rma) {  // always: which code ran is part of every result
    std::fprintf(stderr, "%s: rma: core/stealing_protocol.hpp over the %s backend, policy %s\n", kProgram.data(),
                 runner.protocol().backend_name().data(), runner.protocol().policy_name().data());
  }
  std::vector<std::uint32_t> counts(wl.n), total(rank == 0 ? wl.n : 0);
  RangeList list = block_allocation(wl.n, static_cast<WorkerId>(ranks))[static_cast<std::size_t>(rank)];
  RangeList log;
  log.reserve(1024);
  const double bytes_before = static_cast<double>(win.bytes_moved());
  result.name = name;
  NoiseWindow noise;
  noise.start();
  bool ok = true;
  for (int f = 0; f < o.frames && ok; ++f) {
    set_frame(f);
    set_phase("frame setup");
    std::fill(counts.begin(), counts.end(), 0u);
    // Between frames (every rank is past the previous frame's done barrier): install, re-arm, reset.
    if (rma) runner.protocol().install(list);
    if (rank == 0) {
      runner.protocol().rearm(static_cast<std::uint32_t>(ranks));  // E4
      win.accumulate_replace(0, kNextItem, std::uint64_t{0});      // central counter
    }
    win.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame start (E1/E2)
    set_phase("frame");
    note_progress();
    const auto t0 = Clock::now();
    Frame fr{f, &counts};
    runner.begin_frame(name);
    if (rma) {
      runner.rma_frame(fr, log);
      list = log;
    } else if (name == "request") {
      runner.request_frame(fr, list, log);
      list = log;
    } else if (name == "central") {
      runner.central_frame(fr);
    } else if (name == "static-space") {
      runner.static_space_frame(fr);
    } else {
      runner.static_frame(fr);
    }
    set_phase("frame done barrier");
    win.sync();
    MPI_Barrier(MPI_COMM_WORLD);  // frame done (E3/E6)
    note_progress();
    // rma-seeded: the next lists are contiguous blocks of equal measured cost (cost_seeded_lists.hpp), from
    // every rank's item times of this frame; the all-reduce is part of this frame's time.
    if (name == "rma-seeded") {
      std::vector<float>& mine = runner.item_costs();
      std::vector<float> all(mine.size());
      MPI_Allreduce(mine.data(), all.data(), static_cast<int>(mine.size()), MPI_FLOAT, MPI_SUM, MPI_COMM_WORLD);
      list = cost_balanced_blocks(all, static_cast<WorkerId>(ranks))[static_cast<std::size_t>(rank)];
      std::fill(mine.begin(), mine.end(), 0.0f);
    }
    result.frame_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    // The audit: counts and triangles reduced to rank 0, the verdict broadcast.
    set_phase("audit");
    MPI_Reduce(counts.data(), total.data(), static_cast<int>(wl.n), MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD);
    std::uint64_t tri = 0;
    MPI_Reduce(&fr.triangles, &tri, 1, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    int verdict = 1;
    if (rank == 0) {
      verdict = audit_frame(name, wl, f, total, tri) ? 1 : 0;
      if (verdict) ++result.audited_frames;
      if (!o.quiet && (f + 1) % 10 == 0) {
        std::fprintf(stderr, "%s: %s: frame %d/%d audited (exactly once, %llu triangles)\n", kProgram.data(),
                     name.c_str(), f + 1, o.frames, static_cast<unsigned long long>(tri));
      }
    }
    MPI_Bcast(&verdict, 1, MPI_INT, 0, MPI_COMM_WORLD);
    ok = verdict == 1;
  }
  result.noise = noise.finish();
  RankStats& stats = runner.finish_stats();
  stats.bytes += static_cast<double>(win.bytes_moved()) - bytes_before;
  stats.t4_wait_s = runner.protocol().t4_wait_s();
  stats.t4_spins = static_cast<double>(runner.protocol().t4_polls());
  result.ranks.resize(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(&stats, kRankStatFields, MPI_DOUBLE, rank == 0 ? result.ranks.data() : nullptr, kRankStatFields,
             MPI_DOUBLE, 0, MPI_COMM_WORLD);
  return ok;
}

}  // namespace frontsteal::mpi
