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

#include <memory>
#include <cstdint>
#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/mpi_workload.hpp"
#include "distributed/rank_stats.hpp"
#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

class FrameRunner;
class HierarchicalRank;
class Lifelines;
class NoiseWindow;

// One scheduler's runner kept across passes (the paired rounds of paired_rounds.hpp run each arm once per
// round): every pass starts from the same lists (block allocation), so every pass runs the same frames; the
// statistics and the noise window span every pass, gathered once by finish(). Collective over MPI_COMM_WORLD.
class SchedulerRun {
 public:
  SchedulerRun(std::string name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
               double owner_progress_us);
  ~SchedulerRun();
  SchedulerRun(const SchedulerRun&) = delete;
  SchedulerRun& operator=(const SchedulerRun&) = delete;

  // Frames 0 .. frames-1, each audited; appends rank 0's frame times to frame_s. `planted_s`: rank 0 spins
  // this long (by the clock) after each frame's done barrier, inside the frame's timed region — a slowdown
  // of known size for testing the comparison method. Returns false when an audit failed.
  bool run_pass(int frames, double planted_s, std::vector<double>& frame_s);
  // Gathers every rank's statistics into `result` (rank 0) and ends the noise window.
  void finish(SchedulerResult& result);
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  const Options& o_;
  Workload& wl_;
  int rank_, ranks_;
  RmaWindow& win_;
  std::unique_ptr<FrameRunner> runner_;
  std::unique_ptr<Lifelines> lifelines_;    // hier with --lifelines on
  std::unique_ptr<HierarchicalRank> hier_;  // hier only
  std::vector<std::uint32_t> counts_, total_;
  std::vector<float> costs_before_;  // rma-seeded, hier-seeded: every rank's item times of the frame before
  std::uint64_t audited_frames_ = 0;
  double bytes_before_ = 0;
  std::unique_ptr<NoiseWindow> noise_;
};

// Runs every frame of `name`; fills result (frame times and gathered stats on rank 0). Returns false when an
// audit failed (rank 0 printed which item of which frame). Collective over MPI_COMM_WORLD.
bool run_scheduler(const std::string& name, const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                   double owner_progress_us, SchedulerResult& result);

}  // namespace frontsteal::mpi
