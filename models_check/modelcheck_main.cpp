// frontsteal-modelcheck — model-check the stealing protocol with Relacy: verdicts per policy and scenario,
// a memory-order mutation kill matrix, and the certificate of the Minimal policy.
//
// This file opens the report with the run's bounds and puts its sections together: the options are
// modelcheck_options.cpp's, the verdicts modelcheck_verdicts.cpp's, the kill matrix, certificate and derivation
// modelcheck_mutation.cpp's, the report's frame checker_report.hpp's. It never includes Relacy (suite_*.cpp do).
#include <cstdio>
#include <string>
#include <vector>

#include "models_check/checker_report.hpp"
#include "models_check/modelcheck_mutation.hpp"
#include "models_check/modelcheck_options.hpp"
#include "models_check/modelcheck_verdicts.hpp"
#include "reporting/table.hpp"

using namespace frontsteal::model;
using namespace frontsteal::model::stealing;
namespace report = frontsteal::report;

namespace {

std::string preamble(const Options& o) {
  std::string searches;
  for (const auto& s : o.searches) searches += " " + s;
  return "# Model-checking results (Relacy)\n\nTier: " + o.tier + "; random search " +
         std::to_string(random_iterations(o)) + " iterations; searches:" + searches + "; execution depth limit " +
         std::to_string(o.depth) + "; spin bound " + std::to_string(o.spin_bound) + " (frame waits " +
         std::to_string(o.spin_bound + 1) + "); tree searches stop at a safety cap of " +
         std::to_string(execution_cap(o)) +
         " executions.\n\n"
         "**Bounds.** Relacy keeps a few stores per atomic and never produces load buffering: a pass is a bounded "
         "search, not a proof. The context-bound (and full) searches run each scenario as a finite program: every "
         "wait and idle round may fail at most the spin bound's number of times (one more for frame waits), and an "
         "execution that would fail once more is discarded, its end-of-execution checks skipped "
         "(models_check/relacy_backend.hpp, SPIN BOUND: a failed poll changes nothing, so a longer wait is "
         "equivalent to one in which the other threads ran first). Such a search is exhaustive within its "
         "context bound: per search the report gives executions run to completion and checked (\"done\") "
         "and executions discarded by the spin bound. \"capped\" would mark a search stopped by the safety "
         "cap, i.e. not exhaustive. The bound gives up liveness: a wait that never ends is discarded, not "
         "reported; the random search runs the unbounded program and still reports livelocks, and a tree "
         "search with no complete execution fails as vacuous. A failure is a real execution of the protocol's "
         "own source (histories name core/ files and lines).\n\n";
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  return run_checker(kProgram, [&] {
    CheckerReport results(kProgram, o.out, /*histories=*/false);
    const auto scens = chosen_scenarios(o);
    bool all_expected = true;
    results.markdown = preamble(o);
    results.json["tool"] = "relacy";
    results.json["tier"] = o.tier;
    results.json["random_iterations"] = random_iterations(o);
    auto add = [&](const char* key, const ReportSection& section) {
      results.markdown += section.markdown;
      results.json[key] = section.json;
    };
    if (o.verdicts) {
      const std::vector<VerdictCell> cells = run_verdicts(o, scens, results.started());
      for (const VerdictCell& c : cells) all_expected = all_expected && c.as_expected;
      add("verdicts", verdict_section(o, cells));
    }
    if (!o.mutants.empty()) add("kill_matrix", kill_matrix_section(o, scens, all_expected, results.started()));
    if (o.certify) {
      bool certified = true;
      add("certificate", certificate_section(o, scens, certified, results.started()));
      all_expected = all_expected && certified;
    }
    if (!o.derive_base.empty()) {
      const PolicyTable derived = derive_minimal(*policy_by_name(o.derive_base), scens, o);
      std::printf("\nDerived from %s (every scenario passes; no single one-step weakening passed):\n%s",
                  o.derive_base.c_str(), describe_table(derived).c_str());
      results.markdown += "## Derivation from " + o.derive_base + "\n\n```\n" + describe_table(derived) + "```\n\n";
    }
    results.markdown += "Total time: " + report::fixed_text(results.seconds(), 2) + " s.\n";
    results.json["seconds"] = results.seconds();
    results.json["all_as_expected"] = all_expected;
    results.write("modelcheck");
    std::printf("\n%s in %.1f s; results: %s, %s\n", all_expected ? "all verdicts as expected" : "UNEXPECTED VERDICTS",
                results.seconds(), results.dir().file("modelcheck.md").c_str(),
                results.dir().file("modelcheck.json").c_str());
    return all_expected ? 0 : 1;
  });
}
