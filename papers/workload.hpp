// workload.hpp — the measured side of papers/: a scene tessellated along the camera path by the real
// schedulers (schedulers/registry.hpp), and the serial per-surface cost trace the simulator replays.
//
// The same path and settings as the main job (schedulers/main_job/frontsteal_main.cpp): an orbit of the whole model,
// then a zoom into a corner, 1 px tolerance, 1280x720. Every measured frame is audited (each surface exactly
// once, triangle count equal to the serial loop's); a failed audit throws.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "measure/machine_info.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/paired_analysis.hpp"
#include "measure/pass_usage.hpp"
#include "measure/round_order.hpp"
#include "papers/cost_trace.hpp"
#include "schedulers/scheduler.hpp"
#include "schedulers/static_scheduler.hpp"
#include "tessellate/frame_workload.hpp"
#include "tessellate/path_scene.hpp"

namespace frontsteal::papers {

struct WorkloadOptions {
  std::string scene = "plant:15906";
  std::string path = "orbit-then-zoom";  // a camera path of tessellate/camera_path.hpp, by name
  int frames = 24;
  int width = 1280, height = 720;
  double tolerance_px = 1;
  std::string data_dir;
};

class PathWorkload {
 public:
  explicit PathWorkload(const WorkloadOptions& options);  // throws what load_scene throws
  PathWorkload(const PathWorkload&) = delete;             // frames_ refers to scene_: neither copied nor moved
  PathWorkload& operator=(const PathWorkload&) = delete;

  ItemId surfaces() const noexcept { return scene_.surfaces(); }
  int frames() const noexcept { return scene_.frames(); }
  const WorkloadOptions& options() const noexcept { return options_; }
  const sched::WorkloadHints& hints() const noexcept { return hints_; }

  // Tessellates surface `id` for frame `f` with worker w's scratch (w < the largest P prepared for).
  void tessellate(int f, ItemId id, WorkerId w) { frames_.run(f, id, w); }
  void prepare_workers(WorkerId workers) { frames_.prepare_workers(workers); }
  std::uint64_t frame_triangles() const { return frames_.frame_triangles(); }

 private:
  WorkloadOptions options_;
  tess::PathScene scene_;
  tess::FrameWorkload frames_;  // over scene_, declared after it
  sched::WorkloadHints hints_;
};

// Serial loop over every frame, `passes` times after a warm-up pass; per surface the mean time (the mean,
// not the median: interrupts and cache misses cost real frames their time too).
// median_of_passes: per surface the median of the passes instead (for a machine shared with other work, where a
// preempted pass would otherwise charge its surface the time another process ran).
CostTrace record_cost_trace(PathWorkload& workload, int passes, const std::string& machine, const std::string& commit,
                            bool median_of_passes = false);

struct MeasuredRun {
  std::string scheduler;
  WorkerId workers = 0;
  std::vector<double> path_ms;  // per repeat, the harness's clock around every run_frame
  measure::ArmRounds rounds;    // per repeat (a round): path time, the CPU speed probe just before it, block 0
  double median_path_ms = 0;
  double frames_per_s = 0;      // frames / median path time
  double utilization_pct = 0;   // Σ busy / Σ (wall × P) over every frame of every repeat
  double imbalance_mean = 0;    // max/mean busy per frame, averaged
  double busy_ms_per_path = 0;  // Σ over workers of time inside items, per run of the path (mean of repeats)
  std::uint64_t steals = 0, lock_waits = 0;
  double cpu_pct = 0;  // the workers' thread CPU time / Σ (wall × P): below utilization's busy share
                       // when a worker lost its CPU (descheduled, or asleep on a lock)
  noise::Usage usage;  // the machine while this cell's paths ran, every repeat (noise_monitor.hpp)
};

struct MeasureOptions {
  std::vector<std::string> schedulers;  // registry names
  std::vector<WorkerId> threads;
  int repeats = 3;  // rounds: every cell and the serial loop once per round, in a fresh random order
  std::uint64_t seed = 1;
  measure::OrderKind order = measure::OrderKind::kRandom;
  std::function<void(const std::string&)> progress;
};

// The machine around a measurement, for the noise verdict of its comparisons (papers/measured_noise.hpp).
struct MeasurementNoise {
  noise::Usage during;                 // from the first repeat's start to the last repeat's end
  std::vector<double> serial_path_ms;  // the serial loop's path time, per repeat: their spread is noise too
  std::vector<double> serial_probe;    // the CPU speed probe around each serial pass (measure/cpu_speed_probe.hpp)
  std::vector<noise::PassUsage> serial_passes;  // what each serial pass's thread did (measure/pass_usage.hpp)
  measure::ArmRounds serial_rounds;             // the serial loop per round, as MeasuredRun::rounds
};

// Rounds (measure/round_order.hpp): every cell and the serial loop once per round, in a fresh random order, each
// timed by this function's clock (the schedulers' own wall_ns are not used), the CPU speed probe taken just
// before each. Also returns the serial loop's
// median path time in *serial_ms, and the noise monitor's samples in *noise, when given. Throws
// std::runtime_error on an audit failure.
std::vector<MeasuredRun> measure_schedulers(PathWorkload& workload, const MeasureOptions& options,
                                            double* serial_ms = nullptr, MeasurementNoise* noise = nullptr);

using frontsteal::cpu_model;  // measure/machine_info.hpp
using frontsteal::median;

}  // namespace frontsteal::papers
