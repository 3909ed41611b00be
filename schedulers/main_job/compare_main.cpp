// frontsteal-compare — any two arms of a frontsteal.json against each other, paired round by round with the main
// job's own analysis (measure/paired_analysis.hpp): the comparisons the table does not show (stealing against
// round robin, two stealing policies ...), from the per-round data the file keeps. This file only parses, reads,
// analyses and prints.
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "reporting/command_line.hpp"
#include "reporting/json.hpp"
#include "reporting/table.hpp"
#include "schedulers/main_job/rounds_json.hpp"

namespace {

namespace ms = frontsteal::measure;
using frontsteal::report::Json;

// "NAME P=K" -> the rounds of that row ("serial" is the serial loop).
bool find_rounds(const Json& doc, const std::string& arm, ms::ArmRounds& out) {
  const auto space = arm.rfind(" P=");
  const std::string name = space == std::string::npos ? arm : arm.substr(0, space);
  const unsigned p = space == std::string::npos ? 1 : static_cast<unsigned>(std::stoul(arm.substr(space + 3)));
  const Json* rounds = nullptr;
  if (name == "serial") {
    rounds = &doc.at("serial").at("rounds");
  } else if (name == "limit") {
    // The limit arm's rounds hold P x L per frame: over P they are its throughput limit per frame.
    for (const Json& row : doc.value("limits", Json::array())) {
      if (row.at("workers").get<unsigned>() != p) continue;
      out = frontsteal::main_job::rounds_from_json(row.at("rounds"));
      for (double& t : out.time) t /= p;
      return true;
    }
    return false;
  } else {
    for (const Json& row : doc.at("results")) {
      if (row.at("scheduler") == name && row.at("workers").get<unsigned>() == p) rounds = &row.at("rounds");
    }
  }
  if (!rounds) return false;
  out = frontsteal::main_job::rounds_from_json(*rounds);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  frontsteal::report::CommandLine cli(
      "frontsteal-compare",
      "Compares arms of a frontsteal.json (schema 3 or 4) round by round with the main job's analysis: per pair, the "
      "ratio of the candidate's time to the reference's (Huber estimate of the per-round log-ratio, segments as "
      "blocks, adjusted for the CPU speed probe), its 95 % interval and the verdict against the margin.",
      "Arms are named \"SCHEDULER P=K\" as in the table, \"serial\", or \"limit P=K\" (the limit arm's throughput "
      "limit per frame, L = 1 / sum of its copies' rates). Exit status: 0; 1 when the file or an arm "
      "is missing; 2 for bad usage.");
  std::string file;
  std::vector<std::string> pairs;
  double margin_pct = 2;
  bool no_adjust = false;
  std::string estimator = "huber";
  cli.app().add_option("file", file, "frontsteal.json")->required();
  cli.app().add_option("pairs", pairs, "CANDIDATE REFERENCE [CANDIDATE REFERENCE ...]")->required();
  cli.option("--margin", margin_pct, "equivalence margin (%)")->type_name("PCT");
  cli.option("--estimator", estimator, "huber or mean (as frontsteal's --estimator)")
      ->type_name("E")
      ->check(CLI::IsMember({"huber", "mean"}));
  cli.flag("--no-adjust", no_adjust, "the raw interval decides instead of the probe-adjusted one");
  cli.parse(argc, argv);
  const ms::Settings settings{.margin = margin_pct / 100,
                              .confidence = 0.95,
                              .adjust_for_probe = !no_adjust,
                              .estimator = estimator == "mean" ? ms::Estimator::kMean : ms::Estimator::kHuber};
  if (pairs.size() % 2 != 0) cli.usage_error("arms come in pairs: CANDIDATE REFERENCE");
  std::ifstream in(file);
  if (!in) {
    std::cerr << "frontsteal-compare: " << file << ": cannot be read\n";
    return 1;
  }
  Json doc;
  try {
    doc = Json::parse(in);
  } catch (const std::exception& e) {
    std::cerr << "frontsteal-compare: " << file << ": not JSON: " << e.what() << '\n';
    return 1;
  }
  frontsteal::report::Table t({{"candidate", "candidate", false},
                               {"reference", "reference", false},
                               {"rounds", "rounds"},
                               {"ratio", "ratio [95% CI]", false},
                               {"verdict", "verdict", false}});
  for (std::size_t i = 0; i < pairs.size(); i += 2) {
    ms::ArmRounds a, b;
    try {
      if (!find_rounds(doc, pairs[i], a) || !find_rounds(doc, pairs[i + 1], b)) {
        std::cerr << "frontsteal-compare: " << file << ": no arm '" << (a.size() ? pairs[i + 1] : pairs[i])
                  << "' with per-round data\n";
        return 1;
      }
    } catch (const std::exception& e) {
      std::cerr << "frontsteal-compare: " << file << ": " << e.what() << '\n';
      return 1;
    }
    const std::vector<ms::RoundPair> paired = ms::pair_rounds(a, b);
    if (paired.empty()) {
      std::cerr << "frontsteal-compare: '" << pairs[i] << "' and '" << pairs[i + 1] << "' never ran in the same round "
                << "(the main job's rounds each hold one P: compare arms of the same P, or either with \"serial\")\n";
      return 1;
    }
    const ms::PairedResult r = ms::analyze_pairs(paired, settings);
    const ms::LogInterval& li = r.chosen();
    using frontsteal::report::fixed_text;
    t.add_row({pairs[i], pairs[i + 1], r.rounds,
               li.valid ? fixed_text(li.ratio(), 3) + " [" + fixed_text(li.ratio_low(), 3) + ", " +
                              fixed_text(li.ratio_high(), 3) + "]"
                        : std::string("-"),
               ms::describe(r)});
  }
  std::cout << t.markdown();
  return 0;
}
