// calibration.hpp — frontsteal-mpi --calibrate: the one-sided latencies (get, put, CAS, fetch-and-op, flush)
// from rank 0 to rank 1, a whole remote steal by core's Thief (one view, and word by word for comparison, with
// the one-sided operations each takes) and the owner's per-item costs (claim, progress call, request poll), as
// medians with 95 % bootstrap intervals; the inputs of the distributed simulator (rma_simulator.hpp).
// The steals: rank 1 installs one list of `capacity` items and never claims; rank 0 steals from it, and after
// each steal (outside the timed region) puts rank 1's End back, so that every timed steal takes a share.
//
// OVER TCP. The first cut's target waited in MPI_Barrier while rank 0 timed its operations; over osc/pt2pt
// every operation needs the target's progress engine (owner_progress.hpp). The reported hang did not reproduce
// (that version completed over TCP in 3.8 s: a barrier's wait loop runs opal_progress too), but nothing bounded
// it either. Now rank 1 spins on MPI_Iprobe until rank 0 sends "done" (an attentive target: the figures are
// the transport's, not a busy owner's), every operation runs for at most --calibrate-op-s seconds (a slow
// transport gives fewer repetitions, not a longer run), and the watchdog (rank_watchdog.hpp) names the
// operation and exits 86 if a single one never completes. The 95 % interval is that of an evenly strided
// subsample's median (at most 500 values), so with 20,000 tightly clustered samples the full median may sit
// a few ns outside it.
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
  double operations = 0;      // one-sided operations per repetition (the remote steals; 0 where not counted)
};

// Collective; rank 0 prints the table (and writes --json). Returns the exit status (2: fewer than 2 ranks).
int calibrate(const Options& o, int rank, int ranks, RmaWindow& win, const ProgressChoice& progress);

// The calibration JSON (docs/results-schema.md: kind "measured", contents "calibration").
report::Json calibration_json(const std::vector<CalibrationRow>& rows, int ranks, const ProgressChoice& progress);

}  // namespace frontsteal::mpi
