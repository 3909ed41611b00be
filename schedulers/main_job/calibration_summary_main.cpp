// frontsteal-calibration-summary — over many `frontsteal --calibrate` runs (and experiments resampled from long
// ones), how often the main job's method gives each verdict when the truth is known (calibration_summary.hpp).
// This file only parses, reads, summarizes and writes.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "measure/machine_info.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "schedulers/main_job/calibration_summary.hpp"

namespace mj = frontsteal::main_job;

int main(int argc, char** argv) {
  frontsteal::report::CommandLine cli(
      "frontsteal-calibration-summary",
      "Reads the calibration arms of frontsteal --calibrate runs (frontsteal-calibration.json or frontsteal.json) and "
      "reports, per P and arm, how often the A/A twin was called faster or slower, how often each planted change "
      "was found and called slower (or faster), and how often the realized planted size lay inside the interval — "
      "each with a Wilson 95 % interval — against the goals (A/A false verdicts <= 5 %, +2 % found >= 80 %, +5 % "
      ">= 95 %, coverage >= 90 %). Every experiment is re-analysed from its per-round data with one margin.",
      "Outputs in DIR: calibration.md and calibration.json. Exit status: 0; 1 when a file cannot be read; 2 for bad "
      "usage.");
  std::vector<std::string> real, long_runs;
  std::string out = "out/calibration";
  double margin_pct = 2;
  std::size_t experiments = 200, rounds = 0;
  std::uint64_t seed = 1;
  bool no_adjust = false;
  cli.app().add_option("files", real, "calibration files, one real experiment each")->type_name("FILE");
  cli.app()
      .add_option("--long", long_runs, "long runs to resample experiments from")
      ->type_name("FILE")
      ->delimiter(',');
  cli.option("--experiments", experiments, "experiments resampled from each long run")->type_name("N");
  cli.option("--rounds", rounds, "rounds per resampled experiment (default: the median of the real runs')")
      ->type_name("R");
  cli.option("--margin", margin_pct, "equivalence margin (%)")->type_name("PCT");
  cli.flag("--no-adjust", no_adjust, "analyse with the raw interval instead of the probe-adjusted one");
  bool no_instances = false;
  cli.flag("--ignore-instances", no_instances,
           "a control: analyse every round as independent, ignoring the scheduler instances the runs name (the "
           "round-level interval, which leaves out how much two instances of the same code differ)");
  cli.seed(seed);
  cli.out(out)->type_name("DIR");
  cli.parse(argc, argv);
  if (real.empty() && long_runs.empty()) cli.usage_error("no files given");
  std::vector<std::vector<mj::CalibrationSeries>> real_series, long_series;
  try {
    for (const auto& f : real) real_series.push_back(mj::read_calibration_file(f));
    for (const auto& f : long_runs) long_series.push_back(mj::read_calibration_file(f));
  } catch (const std::exception& e) {
    std::cerr << "frontsteal-calibration-summary: " << e.what() << '\n';
    return 1;
  }
  if (rounds == 0) {
    std::vector<double> r;
    for (const auto& s : real_series) {
      if (!s.empty()) r.push_back(static_cast<double>(s.front().pairs.size()));
    }
    rounds = r.empty() ? 24 : static_cast<std::size_t>(frontsteal::median(r));
  }
  const frontsteal::measure::Settings settings{
      .margin = margin_pct / 100, .confidence = 0.95, .adjust_for_probe = !no_adjust};
  if (no_instances) {
    mj::ignore_instances(real_series);
    mj::ignore_instances(long_series);
  }
  mj::CalibrationSummary summary =
      mj::summarize_calibration(real_series, long_series, experiments, rounds, settings, seed);
  summary.instances_ignored = no_instances;
  const std::string md = mj::calibration_markdown(summary, frontsteal::cpu_model());
  std::cout << md;
  try {
    const frontsteal::report::ResultsDir dir("frontsteal-calibration-summary", out);
    dir.write("calibration.md", md);
    dir.write_json("calibration.json", mj::calibration_summary_json(summary));
  } catch (const std::exception& e) {
    std::cerr << "frontsteal-calibration-summary: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
