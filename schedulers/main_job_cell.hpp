// main_job_cell.hpp — one scheduler at one P in the main job (Cell), and the per-frame accounting every run
// of it goes through, whether the frame ran in this process or in the openmp-static-steal child.
//
// Why one function for both: the in-process path and the child path gather the same totals and apply the
// same three audits (exactly once, triangles equal to the serial loop's, the tessellation's own audit); written
// once, they cannot drift apart.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/frame_stats.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/noise_monitor.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::main_job {

namespace sc = frontsteal::sched;
namespace nz = frontsteal::noise;

// One scheduler at one P: what the interleaved repeats gathered.
struct Cell {
  std::string scheduler;
  WorkerId workers = 0;
  std::unique_ptr<sc::Scheduler> instance;
  std::unique_ptr<sc::LlvmOpenMpChild> child;      // openmp-static-steal: the child process instead of instance
  std::string unavailable;                         // why this cell could not run ("" when it ran)
  double setup_ms = 0;                             // construction (annealing included)
  std::vector<double> path_ms;                     // per repeat
  std::vector<std::vector<double>> frame_ms;       // [repeat][frame]
  WorkerFrameStats totals;                         // summed over every frame of every repeat
  std::vector<WorkerFrameStats> per_worker;        // [worker], summed over every frame of every repeat
  nz::Usage usage;                                 // the machine while this cell's paths ran (all repeats)
  std::vector<std::vector<double>> busy_ratio;     // [repeat][frame]: max/min of the workers' busy time
  double busy_over_available = 0, available = 0;   // Σ busy, Σ wall × P (ns)
  double imbalance_sum = 0, imbalance_max = 0;
  std::uint64_t frames_run = 0;
  std::uint64_t audit_failures = 0, triangle_mismatches = 0;
  std::uint64_t tessellation_inconsistencies = 0;  // surfaces × frames whose tessellation audit failed
  std::string first_problem;
  bool failed() const { return audit_failures || triangle_mismatches || tessellation_inconsistencies; }
};

// What one frame of one cell left: its statistics and what its audits need.
struct FrameOutcome {
  const FrameStats& stats;
  const ExecutionAudit& audit;     // exactly once per item
  std::uint64_t triangles = 0;     // the frame's triangle count
  std::uint64_t inconsistent = 0;  // surfaces whose tessellation audit failed
  std::string first_inconsistent;  // the first of them by name, where known ("" otherwise)
};

// Adds frame `f` to the cell's totals and audits it against the serial loop's triangle count; the first
// problem found is kept with its frame. Returns the frame's wall time in ms.
double account_frame(Cell& c, int f, const FrameOutcome& frame, std::uint64_t serial_triangles);

}  // namespace frontsteal::main_job
