// measured_noise.cpp — the noise verdict of the paper's measured comparisons (measured_noise.hpp).
#include "papers/measured_noise.hpp"

#include <algorithm>

#include "reporting/table.hpp"

namespace frontsteal::papers {

namespace {
std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }
}  // namespace

std::string JudgedComparison::text() const {
  std::string v = stats::to_string(c.verdict);
  if (c.verdict != stats::Verdict::kTooFewRepeats) v += std::string(" ") + (c.effect_pct >= 0 ? "+" : "") + fixed(c.effect_pct, 1) + " %";
  if (!reliable()) v = "unreliable (" + v + ")";
  return fixed(c.ratio.median, 3) + " [" + fixed(c.ratio.low, 3) + ", " + fixed(c.ratio.high, 3) + "] " + v;
}

report::Json JudgedComparison::json() const {
  return {{"ratio_median", c.ratio.median}, {"ci95_low", c.ratio.low}, {"ci95_high", c.ratio.high},
          {"pairs", c.pairs}, {"effect_pct", c.effect_pct},
          {"verdict", reliable() ? stats::to_string(c.verdict) : "unreliable"},
          {"verdict_if_reliable", stats::to_string(c.verdict)}, {"reliable", reliable()},
          {"noise_reason", unreliable_because}};
}

MeasuredNoise::MeasuredNoise(const MeasurementNoise& sampled, const noise::Thresholds& thresholds)
    : sampled_(sampled), thresholds_(thresholds), serial_spread_(noise::spread_of(sampled.serial_path_ms)),
      diagnosis_(noise::diagnose_spread(sampled.serial_path_ms, sampled.serial_probe, thresholds.spread,
                                        sampled.serial_passes)) {
  if (const auto x = noise::assess(sampled_.during, thresholds_); x.busy) {
    warnings_.push_back("during the measurement: " + x.reason);
  }
  if (serial_spread_ > thresholds_.spread) {
    warnings_.push_back("the serial loop's repeats spread by " + fixed(100 * serial_spread_, 1) +
                        " % (max/min - 1; threshold " + fixed(100 * thresholds_.spread, 1) + " %); " + diagnosis_.line);
  }
}

JudgedComparison MeasuredNoise::judge(const MeasuredRun& candidate, const MeasuredRun& reference) const {
  JudgedComparison j{stats::compare_paired(candidate.path_ms, reference.path_ms), {}};
  if (!warnings_.empty()) {
    j.unreliable_because = warnings_.front();
  } else if (const auto x = noise::assess(candidate.usage, thresholds_); x.busy) {
    j.unreliable_because = candidate.scheduler + " P=" + std::to_string(candidate.workers) + ": " + x.reason;
  } else if (const auto y = noise::assess(reference.usage, thresholds_); y.busy) {
    j.unreliable_because = reference.scheduler + " P=" + std::to_string(reference.workers) + ": " + y.reason;
  }
  return j;
}

std::string MeasuredNoise::line() const {
  return "Noise monitor (/proc): other processes " + fixed(100 * sampled_.during.other_share(), 1) + " %, steal " +
         fixed(100 * sampled_.during.steal_share(), 1) + " % of the machine during the measurement; the serial "
         "loop's repeats spread " + fixed(100 * serial_spread_, 1) + " % (thresholds: " +
         fixed(100 * thresholds_.other_share, 0) + " % busy, " + fixed(100 * thresholds_.steal_share, 0) +
         " % steal, " + fixed(100 * thresholds_.spread, 0) + " % spread)" +
         (warnings_.empty() ? std::string(".") : ": every verdict of it is unreliable.");
}

report::Json MeasuredNoise::json() const {
  const noise::Usage& u = sampled_.during;
  return {{"during", {{"wall_s", u.wall_s}, {"windows", u.windows}, {"ticks", u.total_ticks},
                      {"other_share", u.other_share()}, {"steal_share", u.steal_share()},
                      {"busy", noise::assess(u, thresholds_).busy}}},
          {"serial_path_ms_per_repeat", sampled_.serial_path_ms}, {"serial_spread_pct", 100 * serial_spread_},
          {"cpu_probe_ns_per_million_steps", sampled_.serial_probe}, {"cpu_probe_spread_pct", 100 * diagnosis_.probe_spread},
          {"cpu_probe_correlation", diagnosis_.correlation}, {"cpu_varied", diagnosis_.cpu_varied},
          {"cpu_probe_follows_passes", diagnosis_.probe_follows_passes},
          {"serial_passes", noise::pass_usage_columns(sampled_.serial_passes)},
          {"serial_same_work_on_cpu", diagnosis_.same_work_on_cpu},
          {"spread_diagnosis", diagnosis_.line},
          {"busy_threshold_pct", 100 * thresholds_.other_share}, {"spread_threshold_pct", 100 * thresholds_.spread},
          {"warnings", warnings_}};
}

void VerdictTally::add(const JudgedComparison& j) {
  ++verdicts;
  if (j.reliable()) return;
  ++unreliable;
  if (std::find(reasons.begin(), reasons.end(), j.unreliable_because) == reasons.end()) reasons.push_back(j.unreliable_because);
}

std::string VerdictTally::warning() const {
  if (unreliable == 0) return {};
  std::string w = "WARNING: noisy machine: " + std::to_string(unreliable) + " of " + std::to_string(verdicts) +
                  " measured verdicts are marked unreliable. Reasons:\n";
  for (const std::string& r : reasons) w += "  - " + r + "\n";
  return w;
}

}  // namespace frontsteal::papers
