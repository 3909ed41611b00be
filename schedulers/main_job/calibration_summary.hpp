// calibration_summary.hpp — the rates that say whether the main job's verdicts can be trusted on a machine:
// over many runs of `frontsteal --calibrate` (each file one real experiment) and over experiments resampled
// from long runs, how often the A/A twin was called faster or slower, how often each planted change was found
// (the interval beyond 0 on its side) and called slower / faster (beyond the margin), and how often the realized
// planted size lay inside the interval.
//
// Every experiment is analysed again here with measure::analyze_pairs from the per-round data the files carry,
// with one margin and one choice of interval for all of them, so that files written with other settings still
// count alike. A resampled experiment is `rounds` rounds drawn without replacement from one long run
// (measure::subset_of_rounds): it treats the run's rounds as exchangeable, which the random order within
// rounds is there to make them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "measure/calibration_tally.hpp"
#include "measure/paired_analysis.hpp"
#include "reporting/json.hpp"

namespace frontsteal::main_job {

// One calibration comparison of one file: the arm, its P, the planted change it realized, and its rounds.
struct CalibrationSeries {
  std::string source, arm;
  unsigned workers = 0;
  double nominal = 0, realized = 0;  // fractions of time (the speed-up: negative)
  std::vector<measure::RoundPair> pairs;
};

// Reads the "arms" of a frontsteal-calibration.json (or the "calibration" of a frontsteal.json). Throws
// std::runtime_error naming the file and what is missing.
std::vector<CalibrationSeries> read_calibration_file(const std::string& path);

// The tally key: "P=2 A/A", "P=1 +5 %", "P=2 speed-up 5 %".
std::string tally_key(const CalibrationSeries& s);

struct CalibrationSummary {
  std::map<std::string, measure::CalibrationTally> real, resampled;  // by tally_key
  std::size_t real_files = 0, long_runs = 0, resampled_each = 0, resampled_rounds = 0;
  std::vector<std::size_t> real_rounds;  // rounds of each real experiment
  measure::Settings settings;
  bool instances_ignored = false;  // every round analysed as independent (--ignore-instances, a control)
};

// Every round as if no instance had been named: the round-level interval, for comparison with the clustered one.
void ignore_instances(std::vector<std::vector<CalibrationSeries>>& files);

// `real`: one experiment per file. `long_runs`: `experiments` experiments of `rounds` rounds each from each.
CalibrationSummary summarize_calibration(const std::vector<std::vector<CalibrationSeries>>& real,
                                         const std::vector<std::vector<CalibrationSeries>>& long_runs,
                                         std::size_t experiments, std::size_t rounds, const measure::Settings& settings,
                                         std::uint64_t seed);

// The markdown report (tables with Wilson 95 % intervals on every rate, and the acceptance lines) and its JSON.
std::string calibration_markdown(const CalibrationSummary& s, const std::string& machine);
report::Json calibration_summary_json(const CalibrationSummary& s);

// The Wilson score interval (95 %) of a proportion k / n: {low, high}.
std::pair<double, double> wilson_interval(std::size_t k, std::size_t n);

}  // namespace frontsteal::main_job
