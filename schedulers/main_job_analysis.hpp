// main_job_analysis.hpp — what the main job's measurements say: per scheduler and P the medians, speed-up,
// utilization and the two paired comparisons (against the serial loop and against queue-mutex at the same P)
// with their verdicts, marked unreliable where the noise monitor says the machine was not ours; the
// round-robin cost spread; and the one-line summaries the terminal, frontsteal.md and frontsteal.json share.
//
// Why apart from the writers: the table, the JSON and the plots (main_job_tables.hpp, main_job_json.hpp,
// main_job_plots.hpp) read one Analysis, so they cannot disagree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/paired_comparison.hpp"
#include "reporting/json.hpp"
#include "schedulers/cpu_speed_probe.hpp"
#include "schedulers/main_job_report.hpp"
#include "schedulers/round_robin_spread.hpp"

namespace frontsteal::main_job {

namespace st = frontsteal::stats;
namespace report = frontsteal::report;

// One comparison as the table shows it: the verdict, or "unreliable (verdict)" when the noise monitor says
// the machine was not ours while it was measured.
struct ShownComparison {
  st::Comparison c;
  bool reliable = true;
  std::string noise_reason;  // why not reliable
  std::string verdict_text() const;
  std::string interval_text() const;
  report::Json json() const;
};

struct Row {
  const Cell* cell = nullptr;
  double path_ms = 0, fps = 0, speedup = 0, ideal_pct = 0, utilization = 0, imbalance_mean = 0;
  double cpu_pct = 0, off_cpu_pct = 0, spread_pct = 0;
  ShownComparison vs_serial;
  std::optional<ShownComparison> vs_queue;  // absent for queue-mutex itself, or when it was not run
};

struct SpreadRow {
  WorkerId p;
  sc::CostSpread measured, estimated;
  std::optional<sc::CostSpread> busy;  // from the round-robin row, when it ran at this P
};

// Everything the table, the files and the closing lines say.
struct Analysis {
  double t1_ms = 0, serial_spread = 0;
  nz::SpreadDiagnosis spread_diagnosis;  // the CPU speed probe against the serial spread (cpu_speed_probe.hpp)
  nz::Usage before_usage, during_usage, after_usage;
  std::vector<std::string> noise_warnings;  // run-wide reasons: every verdict is unreliable
  std::vector<Row> rows;
  std::size_t verdicts = 0, unreliable = 0;
  bool problems = false;
  std::vector<SpreadRow> spreads;
  double co_runner_core_share = 0;
  std::uint64_t serial_inconsistencies = 0, capped_total = 0, capped_max = 0;
  std::string machine, path_line, spread_line, noise_line, spread_summary, interference_line, warning,
      tessellation_audit, child_note;
};

// Per frame, the median over repeats.
std::vector<double> frame_medians(const std::vector<std::vector<double>>& per_repeat, int frames);

Analysis analyze(const Measured& m);

}  // namespace frontsteal::main_job
