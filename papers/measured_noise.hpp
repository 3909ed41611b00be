// measured_noise.hpp — may a measured comparison of frontsteal-paper be believed, and what does it say? The main
// job's rules (measure/paired_analysis.hpp, measure/noise_monitor.hpp) applied to the paper's measured rows
// (Table 1, Fig. 8).
//
// A comparison is a paired one over rounds (workload.hpp: every cell and the serial loop once per round, random
// order): the per-round log-ratio of the candidate's path time to the reference's, its Huber estimate with a
// Student-t 95 % interval (adjusted for the CPU speed probe when the rounds allow it: 4 or more), and a verdict
// against the margin (faster / slower /
// equivalent / inconclusive). It is *unreliable* only when other processes or the hypervisor took more than the
// thresholds' share of the machine — during the whole measurement (then every comparison of it), or during the
// paths of either of its two cells. The spread of single serial passes is reported, not used: the paired rounds
// carry the verdict. An unreliable comparison keeps its numbers, and its verdict reads "unreliable (...)".
#pragma once

#include <string>
#include <vector>

#include "measure/cpu_speed_probe.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/paired_analysis.hpp"
#include "papers/workload.hpp"
#include "reporting/json.hpp"

namespace frontsteal::papers {

struct JudgedComparison {
  measure::PairedResult c;
  std::string unreliable_because;  // empty: reliable
  bool reliable() const noexcept { return unreliable_because.empty(); }
  // "0.912 [0.880, 0.950] faster -8.8 %", or "... unreliable (faster -8.8 %)".
  std::string text() const;
  // ratio, ci95_low, ci95_high, pairs, effect_pct, verdict ("unreliable" when it is), verdict_if_reliable,
  // reliable, noise_reason, and the raw and adjusted intervals.
  report::Json json() const;
};

// How a measured comparison of `rounds` rounds is judged, in one sentence fragment for the reports: the
// estimator and interval of measure/paired_analysis.hpp and the margin of the verdicts.
std::string comparison_method(int rounds, const measure::Settings& settings = {});

class MeasuredNoise {
 public:
  explicit MeasuredNoise(const MeasurementNoise& sampled, const noise::Thresholds& thresholds = {},
                         const measure::Settings& settings = {});

  // Candidate against reference, paired by repeat, judged by the noise while the two ran.
  JudgedComparison judge(const MeasuredRun& candidate, const MeasuredRun& reference) const;
  // Reasons that make every comparison of this measurement unreliable (empty: none).
  const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  // One line for the markdown: others' and steal share during the measurement, the serial spread, thresholds.
  std::string line() const;
  report::Json json() const;

 private:
  MeasurementNoise sampled_;
  noise::Thresholds thresholds_;
  measure::Settings settings_;
  double serial_spread_ = 0;
  noise::SpreadDiagnosis diagnosis_;  // the CPU speed probe against the serial spread
  std::vector<std::string> warnings_;
};

// Counts the verdicts a run printed and the unreliable ones, for the closing warning.
struct VerdictTally {
  std::size_t verdicts = 0, unreliable = 0;
  std::vector<std::string> reasons;  // distinct, in order
  void add(const JudgedComparison& j);
  // "WARNING: k of n measured verdicts are unreliable. Reasons: ..." (empty when none).
  std::string warning() const;
};

}  // namespace frontsteal::papers
