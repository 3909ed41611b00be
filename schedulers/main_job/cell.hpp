// cell.hpp — one scheduler at one P in the main job (Cell), and the per-frame accounting every run
// of it goes through, whether the frame ran in this process or in the openmp-static-steal child.
//
// Why one function for both: the in-process path and the child path gather the same totals and apply the
// same three audits (exactly once, triangles equal to the serial loop's, the tessellation's own audit); written
// once, they cannot drift apart.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/frame_stats.hpp"
#include "measure/heap_offset.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/paired_analysis.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::main_job {

namespace sc = frontsteal::sched;
namespace nz = frontsteal::noise;

// What an arm of the experiment is: a scheduler the user asked about, or a calibration arm (a copy of the
// --calibrate-base scheduler under a second name, with or without planted work) that tests the method itself.
enum class ArmRole { kScheduler, kTwin, kPlanted };

// One scheduler at one P (or one calibration arm): what the rounds gathered.
struct Cell {
  std::string scheduler;  // the registry name (a calibration arm: its base's)
  std::string label;      // as shown: the scheduler's name, or e.g. "queue-mutex (A/A twin)", "queue-mutex +5 %"
  ArmRole role = ArmRole::kScheduler;
  double planted = 0;                        // planted extra work, as a fraction of the base's frame time
  std::vector<std::uint64_t> planted_steps;  // per frame: CPU-probe steps spun after the frame, inside the timing
  WorkerId workers = 0;
  measure::HeapOffset heap_offset;  // held while `instance` lives: a random shift of its memory
  std::unique_ptr<sc::Scheduler> instance;
  int instance_id = 0;                            // counts the instances built (recorded with every round)
  std::unique_ptr<sc::LlvmOpenMpChild> child;     // openmp-static-steal: the child process instead of instance
  std::string unavailable;                        // why this cell could not run ("" when it ran)
  double setup_ms = 0;                            // construction (annealing included)
  std::vector<double> path_ms;                    // per pass (the sum of its rounds)
  std::vector<std::vector<double>> frame_ms;      // [pass][frame], the harness's clock
  measure::ArmRounds rounds;                      // per round: the segment's time (ms, the harness's clock),
                                                  // the CPU speed probe just before the arm ran, the segment
  std::vector<double> round_planted_ms;           // [round]: of rounds.time, the planted work's time
  double clock_gap_max_ms = 0;                    // largest |harness - planted - scheduler's wall_ns| per frame
  std::uint64_t clock_gap_frames = 0;             // frames whose gap exceeds kClockGapBoundMs + 5 %
  WorkerFrameStats totals;                        // summed over every frame of every pass
  std::vector<WorkerFrameStats> per_worker;       // [worker], summed over every frame of every pass
  nz::Usage usage;                                // the machine while this cell's segments ran (all passes)
  std::vector<std::vector<double>> busy_ratio;    // [pass][frame]: max/min of the workers' busy time
  double busy_over_available = 0, available = 0;  // Σ busy, Σ wall × P (ns)
  double imbalance_sum = 0, imbalance_max = 0;
  std::uint64_t frames_run = 0;
  std::uint64_t audit_failures = 0, triangle_mismatches = 0;
  std::uint64_t tessellation_inconsistencies = 0;  // surfaces × frames whose tessellation audit failed
  std::string first_problem;
  bool failed() const { return audit_failures || triangle_mismatches || tessellation_inconsistencies; }
};

// The harness's clock and the scheduler's own frame time may differ by the call's entry and exit (thread
// wake-up, the return) but not by more than this plus 5 % of the frame: beyond it, a frame is counted and
// reported (a scheduler whose clock misses part of its own work).
inline constexpr double kClockGapBoundMs = 1.0;

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
