// simulator_validation.hpp — the distributed simulator set beside frontsteal-mpi's own measurements: re-run a
// measured run (frontsteal-mpi --json: its ranks, scene, items, frames, --work-ns, --skew) in the model, with a
// calibration's latencies, and compare each scheduler's frame time RELATIVE TO static round robin in the same
// run. Ratios, not absolute times: the model prices an item at its nominal --work-ns, while the measured item
// also pays this machine's clock, caches and co-runners; a ratio cancels what every scheduler pays alike and
// keeps what the model is for (what a scheduler wins or loses against static). The error of a ratio is
// SIMULATED / measured - 1.
// What cannot be compared: runs with more ranks than cores (the model gives every rank a core), and the
// tessellation scenes (the model prices synthetic shapes only); both are refused with the reason.
#pragma once

#include <string>
#include <vector>

#include "distributed/rma_simulator.hpp"

namespace frontsteal::mpi::sim {

struct MeasuredScheduler {
  std::string name;
  double median_frame_ms = 0;
};

struct MeasuredRun {
  std::string path, scene;
  int ranks = 0;
  Workload workload;
  std::vector<MeasuredScheduler> schedulers;
  std::string assumed;  // keys the file lacked and the defaults used for them ("" when none)
};

// Reads frontsteal-mpi --json output; throws naming the file and what is wrong with it.
MeasuredRun read_measured_run(const std::string& path);

struct ValidationRow {
  std::string scheduler;
  double measured_ms = 0, simulated_ms = 0;
  double measured_ratio = 0, simulated_ratio = 0;  // frame time / static round robin's
  double ratio_error = 0;                          // simulated_ratio / measured_ratio - 1
  bool exactly_once = true;                        // the model's audit
};

// One row per measured scheduler the model has, the reference (static) included with ratio 1. Throws when the
// run has no static round robin to relate to.
std::vector<ValidationRow> validate(const MeasuredRun& run, const Latencies& lat);

}  // namespace frontsteal::mpi::sim
