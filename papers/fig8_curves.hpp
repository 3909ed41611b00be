// fig8_curves.hpp — the paper's Fig. 8 as data: tessellation rate against P for static, global queue, load
// stealing (and Chase–Lev, the modern baseline), MEASURED at P = 1 ... cores and SIMULATED at P = 1 ... --max-p.
//
// `fig8` measures the real schedulers on each stand-in, records the scene's cost trace and replays it through
// the models; `simulate` replays a trace file only (no measured points). Both hand their SceneCurves to
// write_fig8 (fig8_report.hpp). The measured comparisons are the two the paper's text makes — the queue
// against static, stealing against the queue — paired by repeat and judged by the noise monitor
// (measured_noise.hpp).
#pragma once

#include <array>
#include <iterator>
#include <string>
#include <vector>

#include "papers/measured_noise.hpp"
#include "papers/paper_run.hpp"
#include "papers/simulator.hpp"
#include "reporting/json.hpp"

namespace frontsteal::papers {

struct ModelSpec {
  Model model;
  const char* label;      // in tables and plots
  const char* scheduler;  // the registry scheduler it models
};
inline constexpr ModelSpec kFig8Models[] = {
    {Model::static_list, "static (spatial partition)", "spatial-annealing"},
    {Model::queue, "global queue (mutex)", "queue-mutex"},
    {Model::stealing, "load stealing (Fenced)", "stealing/Fenced"},
    {Model::chase_lev, "Chase-Lev", "chase-lev"},
};
inline constexpr std::size_t kFig8ModelCount = std::size(kFig8Models);
inline constexpr std::size_t kStaticModel = 0, kQueueModel = 1, kStealingModel = 2;

template <class T>
using PerModel = std::array<T, kFig8ModelCount>;

struct SceneCurves {
  std::string scene;
  std::size_t surfaces = 0;
  double serial_fps = 0;  // from the trace's Σ costs
  std::vector<WorkerId> sim_ps, meas_ps;
  std::vector<PerModel<SimulatedRun>> sim;                  // [P index][model]
  std::vector<PerModel<double>> meas_fps;                   // [P index][model]
  std::vector<PerModel<double>> sim_at_meas_fps;            // simulated at the measured P
  std::vector<PerModel<double>> meas_busy_ms;               // Σ busy per path run, measured
  std::vector<PerModel<double>> meas_cpu_pct;               // workers' CPU time / (wall × P), measured
  std::vector<PerModel<std::vector<double>>> meas_path_ms;  // [P index][model]: per repeat
  // [P index]: global queue / static, load stealing / global queue (path-time ratios), judged.
  std::vector<std::array<JudgedComparison, 2>> meas_verdicts;
  std::string noise_line;  // empty: nothing measured
  report::Json noise;      // null: nothing measured
};

// The simulated curves of one trace (P = 1 ... --max-p, every model, each audited).
SceneCurves curves_for_trace(const CostTrace& t, const Overheads& ov, PaperRun& run);

// `fig8`: every stand-in (or --scenes) measured, traced and simulated; fig8.{md,csv,json,gp,png}.
int run_fig8(PaperRun& run);
// `simulate`: --trace (default DIR/trace-<scene>.txt) replayed; simulate-<scene>.{md,csv,json,gp,png}.
// Exit status 2 when the trace cannot be read.
int run_simulate(PaperRun& run);

}  // namespace frontsteal::papers
