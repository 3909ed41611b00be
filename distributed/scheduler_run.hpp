// scheduler_run.hpp — every frame of one scheduler across the ranks, with the per-frame exactly-once audit.
//
// FRAME BOUNDARY. Two barriers a frame (start, done); between frames each rank installs its next list (rma),
// rank 0 re-arms the active count (E4) and the central counter. Lists carry over (§4.2.1): a rank's next
// list is what it processed this frame (rma, request).
// AUDIT. Every frame: per-item execution counts reduced to rank 0 (MPI_Reduce); each must be 1; the frame's
// triangle count must equal a serial loop's. A failure prints "AUDIT FAILED" and every rank stops (the
// verdict is broadcast). Negative controls: --plant-defect skip-reread with --force-overlap (rma) and
// --plant-defect request-keeps-share (request); tests/CMakeLists.txt runs both.
#pragma once

#include <string>

#include "distributed/mpi_options.hpp"
#include "distributed/mpi_workload.hpp"
#include "distributed/rank_stats.hpp"
#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

// Runs every frame of `name`; fills result (frame times and gathered stats on rank 0). Returns false when an
// audit failed (rank 0 printed which item of which frame). Collective over MPI_COMM_WORLD.
bool run_scheduler(const std::string& name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                   double owner_progress_us, SchedulerResult& result);

}  // namespace frontsteal::mpi
