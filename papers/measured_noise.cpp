// measured_noise.cpp — the noise verdict of the paper's measured comparisons (measured_noise.hpp).
#include "papers/measured_noise.hpp"

#include <algorithm>

#include "reporting/table.hpp"

namespace frontsteal::papers {

namespace {
std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }
}  // namespace

std::string comparison_method(int rounds, const measure::Settings& settings) {
  const std::string m = fixed(100 * settings.margin, 0);
  return "the " + std::string(measure::to_string(settings.estimator)) + " of the " + std::to_string(rounds) +
         " per-round path-time log-ratios (rounds in a fresh random order, every scheduler a fresh instance at a "
         "random heap offset in every round) with its " +
         fixed(100 * settings.confidence, 0) + " % Student-t interval" +
         (settings.adjust_for_probe ? ", adjusted for the CPU speed probe when that can be computed" : "") +
         "; verdict against a ±" + m +
         " % margin: faster or slower when the whole interval lies beyond it, "
         "equivalent when it lies inside, inconclusive otherwise; effect = change in path time";
}

std::string JudgedComparison::text() const {
  const measure::LogInterval& li = c.chosen();
  std::string v = measure::to_string(c.decision);
  if (li.valid) v += std::string(" ") + (li.effect_pct() >= 0 ? "+" : "") + fixed(li.effect_pct(), 1) + " %";
  if (!reliable()) v = "unreliable (" + v + ")";
  if (!li.valid) return v;
  return fixed(li.ratio(), 3) + " [" + fixed(li.ratio_low(), 3) + ", " + fixed(li.ratio_high(), 3) + "] " + v;
}

report::Json JudgedComparison::json() const {
  const measure::LogInterval& li = c.chosen();
  auto interval = [](const measure::LogInterval& x) -> report::Json {
    if (!x.valid) return nullptr;
    return {{"ratio", x.ratio()}, {"ci95_low", x.ratio_low()}, {"ci95_high", x.ratio_high()}, {"sd_per_round", x.sd}};
  };
  auto number = [&](double v) { return li.valid ? report::Json(v) : report::Json(nullptr); };  // no interval: null
  return {{"ratio", number(li.ratio())},
          {"ci95_low", number(li.ratio_low())},
          {"ci95_high", number(li.ratio_high())},
          {"pairs", c.rounds},
          {"effect_pct", number(li.effect_pct())},
          {"verdict", reliable() ? measure::to_string(c.decision) : "unreliable"},
          {"verdict_if_reliable", measure::to_string(c.decision)},
          {"reliable", reliable()},
          {"noise_reason", unreliable_because},
          {"margin_pct", 100 * c.margin},
          {"interval", c.uses_adjusted ? "probe-adjusted t" : "raw t"},
          {"raw", interval(c.raw)},
          {"adjusted", interval(c.adjusted)},
          {"variance_removed", c.variance_removed}};
}

MeasuredNoise::MeasuredNoise(const MeasurementNoise& sampled, const noise::Thresholds& thresholds,
                             const measure::Settings& settings)
    : sampled_(sampled),
      thresholds_(thresholds),
      settings_(settings),
      serial_spread_(noise::spread_of(sampled.serial_path_ms)),
      diagnosis_(noise::diagnose_spread(sampled.serial_path_ms, sampled.serial_probe, thresholds.spread,
                                        sampled.serial_passes)) {
  if (const auto x = noise::assess(sampled_.during, thresholds_); x.busy) {
    warnings_.push_back("during the measurement: " + x.reason);
  }
}

JudgedComparison MeasuredNoise::judge(const MeasuredRun& candidate, const MeasuredRun& reference) const {
  JudgedComparison j{measure::analyze_pairs(measure::pair_rounds(candidate.rounds, reference.rounds), settings_), {}};
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
         fixed(100 * sampled_.during.steal_share(), 1) +
         " % of the machine during the measurement (thresholds: " + fixed(100 * thresholds_.other_share, 0) +
         " % busy, " + fixed(100 * thresholds_.steal_share, 0) + " % steal); single serial passes spread " +
         fixed(100 * serial_spread_, 1) +
         " % (context only: the "
         "verdicts rest on the paired rounds; " +
         diagnosis_.line + ")" + (warnings_.empty() ? std::string(".") : ": every verdict of it is unreliable.");
}

report::Json MeasuredNoise::json() const {
  const noise::Usage& u = sampled_.during;
  return {{"during",
           {{"wall_s", u.wall_s},
            {"windows", u.windows},
            {"ticks", u.total_ticks},
            {"other_share", u.other_share()},
            {"steal_share", u.steal_share()},
            {"busy", noise::assess(u, thresholds_).busy}}},
          {"serial_path_ms_per_repeat", sampled_.serial_path_ms},
          {"serial_spread_pct", 100 * serial_spread_},
          {"cpu_probe_ns_per_million_steps", sampled_.serial_probe},
          {"cpu_probe_spread_pct", 100 * diagnosis_.probe_spread},
          {"cpu_probe_correlation", diagnosis_.correlation},
          {"cpu_varied", diagnosis_.cpu_varied},
          {"cpu_probe_follows_passes", diagnosis_.probe_follows_passes},
          {"serial_passes", noise::pass_usage_columns(sampled_.serial_passes)},
          {"serial_same_work_on_cpu", diagnosis_.same_work_on_cpu},
          {"spread_diagnosis", diagnosis_.line},
          {"busy_threshold_pct", 100 * thresholds_.other_share},
          {"spread_threshold_pct", 100 * thresholds_.spread},
          {"warnings", warnings_}};
}

void VerdictTally::add(const JudgedComparison& j) {
  ++verdicts;
  if (j.reliable()) return;
  ++unreliable;
  if (std::find(reasons.begin(), reasons.end(), j.unreliable_because) == reasons.end())
    reasons.push_back(j.unreliable_because);
}

std::string VerdictTally::warning() const {
  if (unreliable == 0) return {};
  std::string w = "WARNING: " + std::to_string(unreliable) + " of " + std::to_string(verdicts) +
                  " measured verdicts are marked unreliable. Reasons:\n";
  for (const std::string& r : reasons) w += "  - " + r + "\n";
  return w;
}

}  // namespace frontsteal::papers
