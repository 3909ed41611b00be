// main_job_report.hpp — what the main job (frontsteal, frontsteal_main.cpp) measured, and its reporting:
// the verdicts, the noise assessment and the round-robin cost spread computed from it, then the table on
// stdout and frontsteal.{md,csv,json} plus the gnuplot data, script and PNGs, all through reporting/.
//
// Why apart from the main: the main parses, measures and hands over a Measured; how a result is judged and
// written is here, in named pieces (issue 19 §2), so the measurement loop stays readable.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/execution_counter.hpp"
#include "schedulers/interference.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/noise_monitor.hpp"
#include "schedulers/registry.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::main_job {

namespace sc = frontsteal::sched;
namespace ts = frontsteal::tess;
namespace nz = frontsteal::noise;
namespace fi = frontsteal::interference;

struct Options {
  std::string scene = "plant:15906";
  std::vector<std::string> schedulers;  // empty: all exactly-once ones
  std::vector<WorkerId> threads;
  int frames = 24;
  ts::CameraPathKind path = ts::CameraPathKind::orbit_then_zoom;
  std::optional<fi::InterferenceSpec> interference;  // absent: off
  int repeats = 0;  // 0: auto (see --repeats)
  double budget_s = 180;
  bool pin = false;
  nz::Thresholds noise;
  double tolerance = 1.0;
  ItemId grain = 0;
  int width = 1280, height = 720;
  std::uint64_t seed = 1;
  std::string out = "out";
  bool plot = true;
  bool quiet = false;
  ts::PlantedDefect planted_defect = ts::PlantedDefect::none;
};

// The workload: the scene prepared once, its per-frame views, and one output buffer per surface.
struct Workload {
  ts::Model model;
  std::vector<ts::PreparedSurface> prepared;
  std::vector<ts::TriangleBuffers> buffers;  // per surface: every scheduler writes the same buffers
  std::vector<ts::Camera> cameras;
  std::vector<ts::Frustum> frusta;
  ts::TessellationSettings settings;
  std::vector<std::uint64_t> serial_triangles;  // per frame, from the serial loop: the reference
  std::vector<std::uint64_t> serial_inconsistencies;  // per frame: surfaces whose tessellation audit failed
  std::vector<std::uint64_t> serial_capped;           // per frame: surfaces held at the step cap
};

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
  WorkerFrameStats totals;                     // summed over every frame of every repeat
  std::vector<WorkerFrameStats> per_worker;    // [worker], summed over every frame of every repeat
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

// What the measurement leaves for the report: references into main's state, read only.
struct Measured {
  const Options& o;
  unsigned cores;
  const Workload& wl;
  const ts::DenseRegion& dense;
  const std::vector<std::vector<double>>& item_ns;        // [frame][surface]: warm-up pass, ns
  const std::vector<std::vector<double>>& item_estimate;  // [frame][surface]: cost estimate
  const std::vector<double>& serial_path_ms;
  const std::vector<std::vector<double>>& serial_frame_ms;
  const std::vector<nz::Usage>& serial_usage;
  const std::vector<Cell>& cells;
  const std::vector<Cell>& not_available;
  nz::ProcSample at_start, measure_start, measure_end, at_end;
  std::string repeats_note;
  int co_runner_cpu;  // -1: not pinned (or no co-runner)
};

// The table on stdout; frontsteal.{md,csv,json}, the plot data, script and PNGs in --out (o.out); the noise
// warning and the audit failures last. `elapsed_s`: the run's time so far, for the closing line. Returns the
// exit status: 0, or 1 when an audit failed or a file could not be written.
int write_results(const Measured& m, double elapsed_s);

}  // namespace frontsteal::main_job
