// report.hpp — what the main job (frontsteal, frontsteal_main.cpp) measured (Measured), and its
// reporting: the analysis (analysis.hpp: verdicts, noise, round-robin cost spread), then the table on
// stdout and frontsteal.{md,csv,json} plus the gnuplot data, script and PNGs (tables.hpp,
// json.hpp, plots.hpp), all through reporting/.
//
// Why apart from the main: the main parses, measures (run.hpp) and hands over a Measured; how a result
// is judged and written is here, in named pieces.
#pragma once

#include <string>
#include <vector>

#include "measure/noise_monitor.hpp"
#include "measure/pass_usage.hpp"
#include "schedulers/main_job/cell.hpp"
#include "schedulers/main_job/options.hpp"
#include "schedulers/main_job/workload.hpp"

namespace frontsteal::main_job {

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
  const std::vector<double>& serial_probe;  // the CPU speed probe around each serial pass, ns per 10^6 steps
  const std::vector<nz::PassUsage>& serial_pass_usage;  // what each serial pass's thread did (pass_usage.hpp)
  const measure::ArmRounds& serial_rounds;              // per round: the serial loop's segment time, probe, segment
  const measure::ArmRounds& serial_sampled;             // per round: the serial loop's work on the sampled surfaces
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
