// analysis.hpp — what the main job's measurements say: per scheduler and P the medians, speed-up,
// utilization and the two paired comparisons (against the serial loop and against queue-mutex at the same P)
// from the rounds (measure/paired_analysis.hpp: per-round log-ratios, a t interval, raw and probe-adjusted,
// verdicts against the margin), marked unreliable only where something invalidated them; the short answer
// (stealing against the locked queue and the best other scheduler, per P); the calibration arms' verdicts; the
// round-robin cost spread; and the one-line summaries the terminal, frontsteal.md and frontsteal.json share.
//
// Why apart from the writers: the table, the JSON and the plots (tables.hpp, json.hpp,
// plots.hpp) read one Analysis, so they cannot disagree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "measure/cpu_speed_probe.hpp"
#include "measure/paired_analysis.hpp"
#include "reporting/json.hpp"
#include "schedulers/main_job/report.hpp"
#include "schedulers/main_job/round_robin_spread.hpp"

namespace frontsteal::main_job {

namespace st = frontsteal::stats;
namespace report = frontsteal::report;

// One comparison as the table shows it: the verdict, or "unreliable (verdict)" when something invalidated the
// measurement of this pair (another process took the machine while it ran, an audit failed, the co-runner did not
// run as asked).
struct ShownComparison {
  measure::PairedResult c;
  bool reliable = true;
  std::string noise_reason;  // why not reliable
  std::string verdict_text() const;
  std::string interval_text() const;
  report::Json json() const;
};

// Work inflation from one arm to the serial loop on the sampled surfaces (measure/item_sampler.hpp): per round
// the arm's sampled work over the serial loop's, the same surfaces of the same frames; exp of the estimate.
struct Inflation {
  measure::PairedResult c;
  bool valid() const { return c.chosen().valid; }
  double factor() const { return c.chosen().ratio(); }
};

// Where the time of one scheduler at one P went (loss_account.hpp), against the machine's limit at that P.
struct Account {
  LossAccount terms;                   // shares of P x T, adding up to 1
  std::optional<Inflation> inflation;  // the cell's work against the serial loop's
  // The work split by the limit arm's inflation (the machine's: P busy cores) and what the scheduler adds:
  // work at the limit's speed, and the rest of the work (inflation beyond the limit's), as shares of P x T.
  double work_at_limit = 0, inflation_beyond_limit = 0;
  bool split_by_limit = false;  // both inflations measured
  // The share of P x T the account gives the limit's work: the limit-efficiency it predicts.
  double predicted_limit_efficiency() const { return work_at_limit; }
};

struct Row {
  const Cell* cell = nullptr;
  double path_ms = 0, fps = 0, speedup = 0, ideal_pct = 0, utilization = 0, imbalance_mean = 0;
  double cpu_pct = 0, off_cpu_pct = 0, spread_pct = 0;
  ShownComparison vs_serial;
  std::optional<ShownComparison> vs_queue;       // absent for queue-mutex itself, or when it was not run
  std::optional<ShownComparison> vs_limit;       // T_P / L per round (L: the limit, limit_arm.hpp); efficiency 1 / that
  std::optional<ShownComparison> vs_limit_wall;  // T_P / (W / P): against the limit arm's wall time (a loose bound)
  Account account;
  // limit-efficiency L / T_P with its 95 % interval, from vs_limit (0 without a limit arm)
  double limit_efficiency() const {
    return vs_limit && vs_limit->c.chosen().valid ? 1 / vs_limit->c.chosen().ratio() : 0;
  }
  double limit_efficiency_low() const {
    return vs_limit && vs_limit->c.chosen().valid ? 1 / vs_limit->c.chosen().ratio_high() : 0;
  }
  double limit_efficiency_high() const {
    return vs_limit && vs_limit->c.chosen().valid ? 1 / vs_limit->c.chosen().ratio_low() : 0;
  }
};

// The limit arm at one P (limit_arm.hpp): P serial loops at once.
struct LimitRow {
  const Cell* cell = nullptr;
  double path_ms = 0;                  // median over passes of W summed over the path
  double speedup = 0;                  // T1 / L: the machine's own speed-up at P
  double wall_speedup = 0;             // T1 / (W / P), W the arm's wall time
  ShownComparison vs_serial;           // L / T1 per round
  std::optional<Inflation> inflation;  // one copy's sampled work over the serial loop's: the machine's inflation
  double copy_spread = 0;              // mean over frames of the slowest copy's time over the mean copy's
};

// A calibration arm against its base at the same P, with the planted change it realized (measured by the
// harness's clock: exp(mean over rounds of log(round / (round - planted))) - 1; 0 for the twin). The planted
// speed-up is the base against its +5 % arm (truth 1 / (1 + realized) - 1).
struct CalibrationRow {
  std::string label;
  WorkerId workers = 0;
  double nominal = 0, realized = 0;  // fractions of time
  ShownComparison result;
  const measure::ArmRounds* candidate = nullptr;  // the rounds compared (for the files: re-analysis, resampling)
  const measure::ArmRounds* reference = nullptr;
  bool found() const;    // the interval excludes 0 on the planted side (A/A: never)
  bool covered() const;  // the realized change lies inside the interval
  bool right() const;    // slower / faster / equivalent as planted
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
  std::vector<std::string> noise_warnings;  // run-wide reasons that make every verdict unreliable
  std::vector<std::string> notes;           // context that does not invalidate (the machine before / after)
  std::vector<Row> rows;                    // the schedulers asked about (calibration arms apart)
  std::vector<LimitRow> limits;             // the limit arm at each P it ran at
  std::vector<CalibrationRow> calibration;  // --calibrate
  std::vector<std::string> answer;          // the short answer, one sentence per P and stealing policy
  std::vector<std::string> scale_answer;    // per P: the reference stealing policy against the machine's limit
  std::string design_line;                  // how the verdicts were made
  double median_mde_pct = 0;                // the smallest change found with 80 % power, median over comparisons
  double median_variance_removed_pct = 0;   // by the probe covariate, median over the comparisons with queue-mutex
  std::size_t verdicts = 0, unreliable = 0;
  bool problems = false;
  std::vector<SpreadRow> spreads;
  double co_runner_core_share = 0;
  std::uint64_t serial_inconsistencies = 0, capped_total = 0, capped_max = 0;
  std::string machine, path_line, spread_line, noise_line, spread_summary, interference_line, warning,
      tessellation_audit, remade, child_note;
};

// Per frame, the median over repeats.
std::vector<double> frame_medians(const std::vector<std::vector<double>>& per_repeat, int frames);

Analysis analyze(const Measured& m);

}  // namespace frontsteal::main_job
