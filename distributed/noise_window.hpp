// noise_window.hpp — was the machine (every node) quiet while one scheduler's frames ran? The main job's noise
// monitor (measure/noise_monitor.hpp) over a window, made aware of ranks.
//
// The monitor calls "other processes" every tick of machine-wide busy time that is not its own. Here the
// other ranks on the same node are not noise, they are the measurement: each rank samples /proc before and
// after; rank 0 gathers every rank's counters, groups the ranks by node (MPI_Get_processor_name), and assesses
// each node's usage (its first rank's machine-wide counters) with the sum of its ranks' own ticks as "self".
// Rank 0 gets the worst node's shares and a reason. Collective over MPI_COMM_WORLD (start and finish).
#pragma once

#include <mpi.h>

#include "distributed/rank_stats.hpp"
#include "measure/noise_monitor.hpp"

namespace frontsteal::mpi {

class NoiseWindow {
 public:
  explicit NoiseWindow(noise::Thresholds thresholds = {}) : thresholds_(thresholds) {}
  void start();
  // The verdict (meaningful on rank 0; the others get their node's).
  NoiseVerdict finish();

 private:
  noise::Thresholds thresholds_;
  noise::ProcSample before_;
};

}  // namespace frontsteal::mpi
