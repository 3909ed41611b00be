// frontsteal-mpi — the main job across MPI ranks (paper §7): the frame loop of frontsteal with every
// rank holding the read-only workload (mpi_workload.hpp) and running its items of each frame under four
// schedulers (frame_runner.hpp: rma, request, central, static), every frame audited (scheduler_run.hpp), the
// results reported by rank 0 (mpi_report.hpp); --rounds runs every scheduler in paired rounds with an A/A twin
// and a planted slowdown and decides each comparison (paired_rounds.hpp); --calibrate measures the one-sided latencies
// (calibration.hpp). The protocol itself: core/stealing_protocol.hpp over rma_backend.hpp (window_protocol.hpp); the
// transport's progress: owner_progress.hpp and progress_thread.hpp.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <optional>
#include <string_view>

#include "distributed/calibration.hpp"
#include "distributed/mpi_report.hpp"
#include "distributed/paired_rounds.hpp"
#include "distributed/progress_thread.hpp"
#include "distributed/rank_ledger.hpp"
#include "distributed/rank_watchdog.hpp"
#include "distributed/scheduler_run.hpp"
#include "distributed/window_protocol.hpp"
#include "distributed/window_self_test.hpp"

namespace fm = frontsteal::mpi;

namespace {

// Every scheduler in turn; rank 0 reports. Returns the exit status (0, or 1 for a failed audit or a
// --require-steals run without steals), the same on every rank.
int run_all(const fm::Options& o, fm::Workload& wl, int rank, int ranks, fm::RmaWindow& win,
            const fm::ProgressChoice& progress) {
  std::vector<fm::SchedulerResult> results;
  fm::arm_watchdog();
  int status = 0;
  fm::PairedRun paired;
  if (o.rounds > 0) {
    paired = fm::run_paired_rounds(o, wl, rank, ranks, win, progress.every_us);
    status = paired.ok ? 0 : 1;
    results = paired.results;
  } else {
    for (const std::string& s : o.schedulers) {
      results.emplace_back();
      if (!fm::run_scheduler(s, o, wl, rank, ranks, win, progress.every_us, results.back())) {
        status = 1;
        break;
      }
    }
  }
  for (const fm::SchedulerResult& r : results) {
    double steals = 0;
    for (const fm::RankStats& s : r.ranks) steals += s.steals;
    if (rank == 0 && status == 0 && o.require_steals &&
        (r.name == "rma" || r.name == "request" || r.name == "hier" || r.name == "hier-seeded") && steals == 0) {
      std::fprintf(stderr, "%s: --require-steals: scheduler %s made no steal in %d frames\n", fm::kProgram.data(),
                   r.name.c_str(), o.frames);
      status = 1;
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank == 0 && status == 0) {
    const fm::RunSummary summary{ranks,  o.scene,   wl.n,       o.frames,    progress,       o.work_ns,
                                 o.skew, o.threads, o.chunk_us, o.lifelines, o.batch_claims, o.thief_views};
    if (o.rounds > 0) {
      fm::PairedReport report{
          o.reference, paired.rounds_done, o.frames, o.margin_pct, fm::compare_arms(paired, o.margin_pct), {}};
      report.method = fm::check_method(report.comparisons);
      fm::report_results(o, summary, results, &report);
    } else {
      fm::report_results(o, summary, results);
    }
  }
  return status;
}

// 1 when the window cannot carry the protocols: not the unified memory model (G2 of rma_window.hpp), or its
// one-sided operations return wrong results on this transport (window_self_test.hpp). Collective.
int refuse_unusable_window(fm::RmaWindow& win, int rank) {
  int unified = win.unified() ? 1 : 0, all_unified = 0;
  MPI_Allreduce(&unified, &all_unified, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);  // every rank decides alike
  if (all_unified == 0) {
    if (rank == 0)
      std::fprintf(stderr,
                   "%s: the window's memory model is not MPI_WIN_UNIFIED: the owner's local "
                   "loads and stores would not be coherent with thieves' RMA; refusing to run\n",
                   fm::kProgram.data());
    return 1;
  }
  fm::arm_watchdog();  // an operation that never completes on this transport is reported, not a silent hang
  const fm::WindowSelfTest check = fm::run_window_self_test(win, MPI_COMM_WORLD);
  if (check.ok) return 0;
  if (!check.first_failure.empty()) {
    std::fprintf(stderr, "%s: rank %d: WINDOW SELF-TEST FAILED: %s\n", fm::kProgram.data(), rank,
                 check.first_failure.c_str());
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0)
    std::fprintf(stderr,
                 "%s: the window's one-sided operations return wrong results on this "
                 "transport (window_self_test.hpp); refusing to run\n",
                 fm::kProgram.data());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  const fm::Options o = fm::parse_options(argc, argv);  // before MPI_Init: a bad flag costs no MPI start-up
  if (!o.post_mortem.empty()) {
    try {
      std::printf("%s", fm::describe(fm::read_ledgers(o.post_mortem)).c_str());
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", fm::kProgram.data(), e.what());
      return 2;
    }
  }
  // hier's worker threads run beside the main thread's MPI calls (FUNNELED); a progress thread calls MPI
  // beside the main thread (MULTIPLE).
  const double thread_sleep_us = o.progress_thread_us();
  const int required = thread_sleep_us >= 0 ? MPI_THREAD_MULTIPLE : MPI_THREAD_FUNNELED;
  const char* required_name = thread_sleep_us >= 0 ? "MPI_THREAD_MULTIPLE (--progress-thread)" : "MPI_THREAD_FUNNELED";
  int provided = 0;
  MPI_Init_thread(&argc, &argv, required, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  if (provided < required) {
    if (rank == 0)
      std::fprintf(stderr, "%s: this MPI provides thread level %d, below %s; refusing to run\n", fm::kProgram.data(),
                   provided, required_name);
    MPI_Finalize();
    return 2;
  }
  fm::start_watchdog(o.watchdog_s, rank);
  int status = 0;
  try {
    fm::Workload wl;
    const auto load0 = std::chrono::steady_clock::now();
    fm::build_workload(o, rank, wl);
    fm::open_ledger(o.ledger, rank, ranks, wl.n);
    fm::note_progress();
    fm::RmaWindow win(MPI_COMM_WORLD, std::max<std::uint32_t>(wl.n, 1));
    win.plant_read_before_flush(o.defect == "read-before-flush");
    fm::plant_stale_view(o.defect == "stale-view");
    fm::read_victims_in_views(o.thief_views);
    // A refusal ends this scope normally: the window is freed before MPI_Finalize on every path.
    status = refuse_unusable_window(win, rank);
    std::optional<fm::ProgressThread> progress_thread;  // stopped before the window is freed
    if (status == 0) {
      const fm::ProgressChoice progress = fm::resolve_owner_progress(o.owner_progress, thread_sleep_us, MPI_COMM_WORLD);
      if (thread_sleep_us >= 0) progress_thread.emplace(MPI_COMM_WORLD, thread_sleep_us);
      if (o.calibrate) {
        status = fm::calibrate(o, rank, ranks, win, progress);
      } else {
        if (rank == 0 && !o.quiet) {
          std::fprintf(stderr, "%s: %d ranks, scene %s (%s, %u items), %d frames; prepared in %.2f s; %s\n",
                       fm::kProgram.data(), ranks, o.scene.c_str(), wl.kind.c_str(), wl.n, o.frames,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - load0).count(),
                       progress.describe().c_str());
        }
        status = run_all(o, wl, rank, ranks, win, progress);
      }
      if (progress_thread && rank == 0 && !o.quiet) {
        std::fprintf(stderr, "%s: rank 0's progress thread called MPI_Iprobe %llu times\n", fm::kProgram.data(),
                     static_cast<unsigned long long>(progress_thread->calls()));
      }
    }
    MPI_Barrier(MPI_COMM_WORLD);
    fm::ledger_exit(fm::LedgerState::kFinished);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: rank %d: %s\n", fm::kProgram.data(), rank, e.what());
    if (thread_sleep_us >= 0 && std::string_view(e.what()).find("MPI_Win_allocate") != std::string_view::npos) {
      std::fprintf(stderr,
                   "%s: rank %d: --progress-thread needs a one-sided component that accepts MPI_THREAD_MULTIPLE; "
                   "Open MPI 4.1's osc/pt2pt does not (over TCP use --mca osc ucx; docs/mpi.md)\n",
                   fm::kProgram.data(), rank);
    }
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
