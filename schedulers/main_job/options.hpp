// options.hpp — the main job's (frontsteal) options, and their parsing through report::CommandLine
// (CLI11): every flag, its default, its range, and the usage errors (exit 2, naming the flag).
//
// Why apart from the main: the options are the main job's interface; the measurement (run.hpp) and
// the report (report.hpp) read them, and the main only hands them over.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "measure/interference.hpp"
#include "measure/machine_info.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/paired_analysis.hpp"
#include "measure/round_order.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::main_job {

namespace ts = frontsteal::tess;
namespace nz = frontsteal::noise;
namespace fi = frontsteal::interference;

inline constexpr const char* kProgram = "frontsteal";

struct Options {
  std::string scene = "plant:15906";
  std::vector<std::string> schedulers;  // empty: all exactly-once ones
  std::vector<WorkerId> threads;
  int frames = 24;
  ts::CameraPathKind path = ts::CameraPathKind::orbit_then_zoom;
  std::optional<fi::InterferenceSpec> interference;  // absent: off
  int repeats = 0;                                   // passes over the path; 0: auto (see --repeats)
  double budget_s = 180;
  int round_frames = 1;     // frames per round: the path is split into segments of this many frames
  int instance_frames = 6;  // a fresh instance of every scheduler every this many frames (0: one per run)
  measure::OrderKind order = measure::OrderKind::kRandom;
  double margin = 0.02;  // the verdicts' equivalence margin (fraction of time)
  bool adjust = true;    // verdicts from the CPU-probe-adjusted interval
  measure::Estimator estimator = measure::Estimator::kHuber;
  bool calibrate = false;  // add the calibration arms (A/A twin, planted slowdowns)
  std::string calibrate_base = "queue-mutex";
  bool pin = true;
  bool reuse = false;  // frame-to-frame reuse of unchanged surfaces (tessellate/surface_reuse.hpp)
  bool limit = true;   // the limit arm at every P (limit_arm.hpp)
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

// The analysis settings the options ask for (--margin, --no-adjust, --estimator): every comparison of the run
// is made with these.
inline measure::Settings analysis_settings(const Options& o) {
  return {.margin = o.margin, .confidence = 0.95, .adjust_for_probe = o.adjust, .estimator = o.estimator};
}

// Parses frontsteal's command line. --help prints and exits 0, --list prints the schedulers and exits 0, a
// mistake exits 2 naming the flag. The result is complete: threads and schedulers filled in when not given.
Options parse_options(int argc, char** argv);

}  // namespace frontsteal::main_job
