// calibration_summary.cpp — reading calibration files, tallying real and resampled experiments, and the report
// (calibration_summary.hpp).
#include "schedulers/main_job/calibration_summary.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "reporting/table.hpp"
#include "schedulers/main_job/rounds_json.hpp"

namespace frontsteal::main_job {

namespace {

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

}  // namespace

std::vector<CalibrationSeries> read_calibration_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  report::Json doc;
  try {
    doc = report::Json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
  const report::Json* arms = doc.contains("arms")          ? &doc["arms"]
                             : doc.contains("calibration") ? &doc["calibration"]
                                                           : nullptr;
  if (!arms || !arms->is_array() || arms->empty()) {
    throw std::runtime_error(path + ": no calibration arms (write it with frontsteal --calibrate)");
  }
  std::vector<CalibrationSeries> out;
  for (const auto& a : *arms) {
    try {
      CalibrationSeries s;
      s.source = path;
      s.arm = a.at("arm").get<std::string>();
      s.workers = a.at("workers").get<unsigned>();
      s.nominal = a.at("planted_pct").get<double>() / 100;
      s.realized = a.at("realized_pct").get<double>() / 100;
      s.pairs = measure::pair_rounds(rounds_from_json(a.at("rounds").at("candidate")),
                                     rounds_from_json(a.at("rounds").at("reference")));
      out.push_back(std::move(s));
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": a calibration arm lacks its data: " + e.what());
    }
  }
  return out;
}

std::string tally_key(const CalibrationSeries& s) {
  const std::string p = "P=" + std::to_string(s.workers) + " ";
  if (s.nominal == 0) return p + "A/A twin";
  if (s.nominal < 0) return p + "speed-up " + fixed(-100 * s.nominal, 0) + " %";
  return p + "+" + fixed(100 * s.nominal, 0) + " %";
}

CalibrationSummary summarize_calibration(const std::vector<std::vector<CalibrationSeries>>& real,
                                         const std::vector<std::vector<CalibrationSeries>>& long_runs,
                                         std::size_t experiments, std::size_t rounds, const measure::Settings& settings,
                                         std::uint64_t seed) {
  CalibrationSummary s;
  s.settings = settings;
  for (const auto& file : real) {
    ++s.real_files;
    if (!file.empty()) s.real_rounds.push_back(file.front().pairs.size());
    for (const CalibrationSeries& c : file) {
      measure::CalibrationTally& t = s.real[tally_key(c)];
      t.true_change = c.nominal;
      t.add(measure::analyze_pairs(c.pairs, settings), c.realized);
    }
  }
  s.resampled_each = experiments;
  s.resampled_rounds = rounds;
  for (const auto& file : long_runs) {
    ++s.long_runs;
    const std::size_t total = file.empty() ? 0 : file.front().pairs.size();
    for (std::size_t e = 0; e < experiments && total > rounds; ++e) {
      // One draw of rounds per experiment, shared by every comparison in it (they ran in the same rounds).
      const std::vector<std::size_t> idx = measure::subset_of_rounds(total, rounds, seed + s.long_runs, e);
      for (const CalibrationSeries& c : file) {
        measure::CalibrationTally& t = s.resampled[tally_key(c)];
        t.true_change = c.nominal;
        t.add(measure::analyze_pairs(measure::select_rounds(c.pairs, idx), settings), c.realized);
      }
    }
  }
  return s;
}

std::pair<double, double> wilson_interval(std::size_t k, std::size_t n) {
  if (n == 0) return {0, 1};
  const double z = 1.959963984540054, p = static_cast<double>(k) / static_cast<double>(n);
  const double nn = static_cast<double>(n);
  const double centre = (p + z * z / (2 * nn)) / (1 + z * z / nn);
  const double half = z * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn)) / (1 + z * z / nn);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

namespace {

std::string rate_text(std::size_t k, std::size_t n) {
  const auto [lo, hi] = wilson_interval(k, n);
  return fixed(100.0 * static_cast<double>(k) / static_cast<double>(std::max<std::size_t>(n, 1)), 1) + " % (" +
         std::to_string(k) + "/" + std::to_string(n) + "; " + fixed(100 * lo, 0) + "-" + fixed(100 * hi, 0) + ")";
}

report::Table tally_table(const std::map<std::string, measure::CalibrationTally>& tallies) {
  report::Table t({{"arm", "P and arm", false},
                   {"n", "experiments"},
                   {"false", "false verdict", false},
                   {"found", "found (interval beyond 0)", false},
                   {"right", "planted verdict", false},
                   {"equivalent", "equivalent", false},
                   {"inconclusive", "inconclusive", false},
                   {"covered", "planted size inside", false},
                   {"effect", "mean estimate (%)"}});
  for (const auto& [key, x] : tallies) {
    t.add_row({key, x.experiments, rate_text(x.false_verdicts(), x.experiments),
               x.true_change == 0 ? "false difference " + rate_text(x.false_diff, x.experiments)
                                  : rate_text(x.found, x.experiments),
               rate_text(x.right_verdicts(), x.experiments), rate_text(x.equivalent, x.experiments),
               rate_text(x.inconclusive, x.experiments), rate_text(x.covered, x.experiments),
               fixed(x.mean_effect_pct(), 2)});
  }
  return t;
}

// The acceptance lines: A/A false verdicts <= 5 %, +2 % found >= 80 %, +5 % found >= 95 %, coverage >= 90 %.
std::string acceptance(const std::map<std::string, measure::CalibrationTally>& tallies) {
  std::ostringstream s;
  for (const auto& [key, x] : tallies) {
    if (x.experiments == 0) continue;
    const double cover = x.rate(x.covered);
    if (x.true_change == 0) {
      s << "- " << key << ": false verdicts " << fixed(100 * x.rate(x.false_verdicts()), 1)
        << " % (goal <= 5 %): " << (x.rate(x.false_verdicts()) <= 0.05 ? "met" : "MISSED") << "; coverage "
        << fixed(100 * cover, 1) << " % (goal >= 90 %): " << (cover >= 0.9 ? "met" : "MISSED") << "\n";
    } else {
      const double goal = std::fabs(x.true_change - 0.02) < 1e-9    ? 0.80
                          : std::fabs(x.true_change) >= 0.05 - 1e-9 ? 0.95
                                                                    : 0;
      s << "- " << key << ": found " << fixed(100 * x.rate(x.found), 1) << " %";
      if (goal > 0)
        s << " (goal >= " << fixed(100 * goal, 0) << " %): " << (x.rate(x.found) >= goal ? "met" : "MISSED");
      s << "; called " << (x.true_change > 0 ? "slower" : "faster") << " beyond the margin "
        << fixed(100 * x.rate(x.right_verdicts()), 1) << " %; coverage " << fixed(100 * cover, 1)
        << " % (goal >= 90 %): " << (cover >= 0.9 ? "met" : "MISSED") << "\n";
    }
  }
  return s.str();
}

}  // namespace

void ignore_instances(std::vector<std::vector<CalibrationSeries>>& files) {
  for (auto& file : files) {
    for (CalibrationSeries& c : file) {
      for (measure::RoundPair& p : c.pairs) p.candidate_instance = p.reference_instance = -1;
    }
  }
}

std::string calibration_markdown(const CalibrationSummary& s, const std::string& machine) {
  std::ostringstream md;
  md << "# Calibration of the main job's verdicts (measured)\n\n"
     << "Machine: " << machine << ". Margin +-" << fixed(100 * s.settings.margin, 1) << " %, 95 % Student-t interval "
     << (s.settings.adjust_for_probe ? "adjusted for the CPU speed probe" : "(raw)")
     << ", every experiment re-analysed from its per-round data. Rates with Wilson 95 % intervals. A false verdict is "
        "faster or slower for the A/A twin, the opposite direction for a planted change; found = the interval lies "
        "beyond 0 on the planted side; planted verdict = slower (faster for the speed-up) beyond the margin "
        "(equivalent for the twin); planted size inside = the realized planted change (measured by the harness's "
        "clock) lies in the interval. "
     << (s.instances_ignored ? "**Control: the rounds analysed as independent** (--ignore-instances): the instances "
                               "the runs named are ignored, so the interval leaves out how much instances differ.\n\n"
                             : "Rounds that shared a scheduler instance are analysed as a cluster (cluster-robust "
                               "interval) where the runs named their instances.\n\n");
  if (s.real_files > 0) {
    std::size_t lo = s.real_rounds.empty() ? 0 : *std::min_element(s.real_rounds.begin(), s.real_rounds.end());
    std::size_t hi = s.real_rounds.empty() ? 0 : *std::max_element(s.real_rounds.begin(), s.real_rounds.end());
    md << "## Real runs: " << s.real_files << " runs of `frontsteal --calibrate`, one experiment each (" << lo << "-"
       << hi << " rounds)\n\n"
       << tally_table(s.real).markdown() << "\n"
       << acceptance(s.real) << "\n";
  }
  if (!s.resampled.empty()) {
    md << "## Resampled: " << s.resampled_each << " experiments of " << s.resampled_rounds << " rounds from each of "
       << s.long_runs << " long run(s)\n\nThe experiments share rounds (each draws " << s.resampled_rounds
       << " of the long run's rounds), so they are not independent: the Wilson intervals below treat them as if they "
          "were and are too narrow; the rates themselves are unbiased estimates for a run of this size.\n\n"
       << tally_table(s.resampled).markdown() << "\n"
       << acceptance(s.resampled) << "\n";
  }
  return md.str();
}

report::Json calibration_summary_json(const CalibrationSummary& s) {
  auto tallies = [](const std::map<std::string, measure::CalibrationTally>& m) {
    report::Json out = report::Json::array();
    for (const auto& [key, x] : m) {
      out.push_back({{"arm", key},
                     {"true_change_pct", 100 * x.true_change},
                     {"experiments", x.experiments},
                     {"faster", x.faster},
                     {"slower", x.slower},
                     {"equivalent", x.equivalent},
                     {"inconclusive", x.inconclusive},
                     {"too_few", x.too_few},
                     {"found", x.found},
                     {"false_difference", x.false_diff},
                     {"covered", x.covered},
                     {"false_verdict_rate", x.rate(x.false_verdicts())},
                     {"found_rate", x.rate(x.found)},
                     {"planted_verdict_rate", x.rate(x.right_verdicts())},
                     {"coverage", x.rate(x.covered)},
                     {"mean_estimate_pct", x.mean_effect_pct()}});
    }
    return out;
  };
  return {{"margin_pct", 100 * s.settings.margin},
          {"adjusted", s.settings.adjust_for_probe},
          {"instances_ignored", s.instances_ignored},
          {"real_files", s.real_files},
          {"real_rounds", s.real_rounds},
          {"real", tallies(s.real)},
          {"long_runs", s.long_runs},
          {"resampled_experiments_each", s.resampled_each},
          {"resampled_rounds", s.resampled_rounds},
          {"resampled", tallies(s.resampled)}};
}

}  // namespace frontsteal::main_job
