// calibration.hpp — frontsteal-mpi --calibrate: the one-sided latencies (get, put, CAS, fetch-and-op, flush)
// from rank 0 to rank 1 and the owner's per-item costs (claim, progress call, request poll), as medians with
// 95 % bootstrap intervals; the inputs of the distributed simulator (rma_simulator.hpp).
//
// WHY IT HUNG OVER TCP, AND WHAT IT DOES NOW. Rank 1 used to wait in MPI_Barrier while rank 0 timed its
// operations. Over TCP (osc/pt2pt or osc/rdma on btl/tcp) every operation needs rank 1's progress engine
// (owner_progress.hpp), and a rank blocked in a barrier runs it only as often as the barrier's own wait loop
// polls — and the TCP events, on Open MPI's libevent path, only every few polls: the operations crawled.
// Now rank 1 spins on MPI_Iprobe until rank 0 sends "done" (an attentive target: the figures are the
// transport's, not a busy owner's), every operation runs for at most --calibrate-op-s seconds (so a slow
// transport gives fewer repetitions, not a longer run), and the watchdog (rank_watchdog.hpp) names the
// operation and exits 86 if a single one never completes.
#pragma once

#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/owner_progress.hpp"
#include "distributed/rma_window.hpp"
#include "reporting/json.hpp"

namespace frontsteal::mpi {

struct CalibrationRow {
  std::string operation;
  double median_ns = 0, ci_low_ns = 0, ci_high_ns = 0;
  int repetitions = 0;
  bool time_bounded = false;  // stopped by --calibrate-op-s before the repetition count
};

// Collective; rank 0 prints the table (and writes --json). Returns the exit status (2: fewer than 2 ranks).
int calibrate(const Options& o, int rank, int ranks, RmaWindow& win, const ProgressChoice& progress);

// The calibration JSON (docs/results-schema.md: kind "measured", contents "calibration").
report::Json calibration_json(const std::vector<CalibrationRow>& rows, int ranks, const ProgressChoice& progress);

}  // namespace frontsteal::mpi
