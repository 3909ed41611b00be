// measured_noise.hpp — may a measured comparison of frontsteal-paper be believed? The main job's noise rules
// (schedulers/noise_monitor.hpp) applied to the paper's measured rows (Table 1, Fig. 8).
//
// A comparison is a paired one (core/paired_comparison.hpp: per repeat, the candidate's path time over the
// reference's; median, 95 % bootstrap interval, verdict). It is *unreliable* when, while it was measured,
// other processes or the hypervisor took more than the thresholds' share of the machine — during the whole
// measurement (then every comparison of it), or during the paths of either of its two cells — or when the
// serial loop's repeats spread more than the threshold (a machine whose speed drifts). An unreliable
// comparison keeps its numbers, and its verdict reads "unreliable (...)"; the run prints a warning.
#pragma once

#include <string>
#include <vector>

#include "core/paired_comparison.hpp"
#include "papers/workload.hpp"
#include "reporting/json.hpp"
#include "schedulers/cpu_speed_probe.hpp"
#include "schedulers/noise_monitor.hpp"

namespace frontsteal::papers {

struct JudgedComparison {
  stats::Comparison c;
  std::string unreliable_because;  // empty: reliable
  bool reliable() const noexcept { return unreliable_because.empty(); }
  // "0.912 [0.880, 0.950] ahead -8.8 %", or "... unreliable (ahead -8.8 %)".
  std::string text() const;
  // ratio_median, ci95_low, ci95_high, pairs, effect_pct, verdict ("unreliable" when it is), and
  // verdict_if_reliable, reliable, noise_reason.
  report::Json json() const;
};

class MeasuredNoise {
 public:
  explicit MeasuredNoise(const MeasurementNoise& sampled, const noise::Thresholds& thresholds = {});

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
  double serial_spread_ = 0;
  noise::SpreadDiagnosis diagnosis_;  // the CPU speed probe against the serial spread
  std::vector<std::string> warnings_;
};

// Counts the verdicts a run printed and the unreliable ones, for the closing warning.
struct VerdictTally {
  std::size_t verdicts = 0, unreliable = 0;
  std::vector<std::string> reasons;  // distinct, in order
  void add(const JudgedComparison& j);
  // "WARNING: noisy machine: k of n measured verdicts are unreliable. Reasons: ..." (empty when none).
  std::string warning() const;
};

}  // namespace frontsteal::papers
