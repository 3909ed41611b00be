// paper_run.hpp — one run of frontsteal-paper: what every subcommand shares.
//
// The options, the stamp every artifact carries (machine, commit, date), progress lines on stderr, the results
// directory (--out, created on first use), the simulator's costs (read from --calibration, or measured once per
// run and written as calibration.{txt,md}), and the steps the artifacts have in common: load a scene's
// workload, record its cost trace, simulate a static partition or any model at P workers.
//
// Why one object: table1, fig8 and `all` need the same calibration, and each subcommand is then one function of
// (PaperRun&) → exit status, registered in one line (paper_main.cpp).
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "measure/machine_info.hpp"
#include "papers/calibration.hpp"
#include "papers/cost_trace.hpp"
#include "papers/paper_options.hpp"
#include "papers/simulator.hpp"
#include "papers/workload.hpp"
#include "reporting/json.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::papers {

inline constexpr const char* kPaperProgram = "frontsteal-paper";

std::string machine_line();                          // "<cpu model>, N hardware threads"
std::string today();                                 // YYYY-MM-DD, UTC
std::string fixed(double v, int digits);             // "12.35" for (12.345, 2)
std::string pct_change(double ratio);                // "+3.5%" for 1.035
std::string short_name(const std::string& scene);    // a scene as a file-name part: plant:5302 → plant-5302
std::vector<WorkerId> simulated_ps(WorkerId max_p);  // 1 ... 16, then steps of 4 to 32, of 8 beyond; max_p last
std::vector<WorkerId> measured_ps();                 // 1 ... cores

class PaperRun {
 public:
  // `commit`, `data_dir`: the executable's stamp (FRONTSTEAL_GIT_COMMIT, FRONTSTEAL_DATA_DIR).
  PaperRun(Options options, std::string commit, std::string data_dir);

  const Options& options() const noexcept { return o_; }
  const std::string& commit() const noexcept { return commit_; }
  const std::string& data_dir() const noexcept { return data_dir_; }
  // "Machine: ... Commit ..., run YYYY-MM-DD." under every markdown title.
  std::string stamp() const;

  // A progress line on stderr with the seconds since the start (nothing under --quiet).
  void say(const std::string& line) const;
  // The same, indented, for library code that reports its steps.
  std::function<void(const std::string&)> sink() const;

  // --out, created on first use; throws std::runtime_error naming it when it cannot be.
  const report::ResultsDir& dir();
  // Runs gnuplot on `script` in --out unless --no-plot.
  void plot(std::string_view script);
  // The header of every JSON this program writes (report::document) plus artifact, machine and date.
  report::Json document(int schema_version, std::string_view artifact, std::string_view kind) const;

  // --calibration, or the microbenchmarks (once per run; writes calibration.txt and calibration.md).
  const Overheads& overheads();
  bool calibrated_here() const noexcept { return calibrated_here_; }

  // The scene's path workload (--frames views of the main job's camera path).
  PathWorkload load(const std::string& scene) const;
  // --passes serial passes over `workload`, written to DIR/trace-<scene>.txt.
  CostTrace record_trace(PathWorkload& workload);

 private:
  Options o_;
  std::string commit_, data_dir_;
  std::chrono::steady_clock::time_point start_;
  std::optional<report::ResultsDir> dir_;
  std::optional<Overheads> overheads_;
  bool calibrated_here_ = false;
};

// A static partition at P workers: round robin, or the spatial annealing of the trace's centres and estimates.
SimulatedRun simulate_static(const CostTrace& t, const Overheads& ov, WorkerId p, bool spatial, std::uint64_t seed);
// Any model at P workers (static_list = the spatial partition).
SimulatedRun simulate_model(const CostTrace& t, const Overheads& ov, Model m, WorkerId p, std::uint64_t seed);
// Throws std::runtime_error naming `what` when the simulated run's exactly-once audit failed.
void require_audit(const SimulatedRun& r, const std::string& what);

// `calibrate`: the microbenchmarks (or --calibration), printed; calibration.{txt,md}.
int run_calibrate(PaperRun& run);
// `trace`: --scene's cost trace into --trace (default DIR/trace-<scene>.txt).
int run_trace(PaperRun& run);

}  // namespace frontsteal::papers
