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
#include "schedulers/main_job/limit_arm.hpp"
#include "schedulers/main_job/loss_account.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::main_job {

namespace sc = frontsteal::sched;
namespace nz = frontsteal::noise;

// What an arm of the experiment is: a scheduler the user asked about, a calibration arm (a copy of the
// --calibrate-base scheduler under a second name, with or without planted work) that tests the method itself, or
// the limit arm of one P (limit_arm.hpp: P serial loops at once, the machine's own throughput limit).
enum class ArmRole { kScheduler, kTwin, kPlanted, kLimit };
inline constexpr const char* kLimitName = "limit";

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
  int instance_id = 0;                         // counts the instances built (recorded with every round)
  std::unique_ptr<sc::LlvmOpenMpChild> child;  // openmp-static-steal: the child process instead of instance
  std::unique_ptr<LimitArm> limit;             // the limit arm: its copies instead of instance
  bool sample_items = true;                    // the harness samples its items (SchedulerInfo::account)
  std::string unavailable;                     // why this cell could not run ("" when it ran)
  double setup_ms = 0;                         // construction (annealing included)
  std::vector<double> path_ms;                 // per pass (the sum of its rounds)
  std::vector<std::vector<double>> frame_ms;   // [pass][frame], the harness's clock
  measure::ArmRounds rounds;                   // per round: the segment's time (ms, the harness's clock),
                                               // the CPU speed probe just before the arm ran, the segment
  std::vector<double> round_planted_ms;        // [round]: of rounds.time, the planted work's time
  measure::ArmRounds sampled;                  // per round as `rounds`: the sampled surfaces' work (ms; the
                                               // limit arm: per copy), against the serial loop's: inflation
  AccountSums account;                         // the loss account's sums (loss_account.hpp)
  double limit_copy_spread_sum = 0;            // the limit arm: Σ over frames of its slowest copy / mean copy
  std::vector<double> limit_copy_time_sum;     // the limit arm: per copy, Σ over frames of its time / the mean copy's
  measure::ArmRounds limit_wall;               // the limit arm, per round: release → last copy done (ms)
  // The limit arm's wall time per pass (the sum of its rounds in each pass), as path_ms is for its limit.
  std::vector<double> limit_wall_path_ms() const {
    std::vector<double> out(path_ms.size(), 0.0);
    if (path_ms.empty() || limit_wall.size() == 0) return out;
    const std::size_t per_pass = limit_wall.size() / path_ms.size();
    for (std::size_t k = 0; k < limit_wall.size(); ++k)
      out[std::min(k / std::max<std::size_t>(per_pass, 1), out.size() - 1)] += limit_wall.time[k];
    return out;
  }
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

// One frame of an in-process scheduler as the harness times it: by this thread's clock from before run_frame to
// after it returned (never the scheduler's own FrameStats::wall_ns, which misses whatever the scheduler does
// outside its window), then `planted_steps` of the CPU speed probe's loop spun on this thread (a calibration arm's
// planted work, timed apart).
struct TimedFrame {
  const FrameStats* stats = nullptr;
  double frame_ns = 0;    // run_frame, by the harness's clock
  double planted_ns = 0;  // the planted work after it
};
TimedFrame time_frame(sc::Scheduler& scheduler, sc::ItemFunctionRef item, std::uint64_t planted_steps);

}  // namespace frontsteal::main_job
