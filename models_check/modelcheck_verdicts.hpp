// modelcheck_verdicts.hpp — frontsteal-modelcheck's first section: every chosen policy × scenario (and, for an
// at-least-once policy, both checks), each cell searched by the run's searches up to its first failure and judged
// against the expected-verdict table (expected_verdicts.hpp). Free of Relacy (run_scenario() runs the searches).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "models_check/checker_report.hpp"
#include "models_check/modelcheck_options.hpp"

namespace frontsteal::model::stealing {

struct SearchRecord {
  std::string search;
  SearchResult result;
};

struct VerdictCell {
  std::string policy;
  std::string scenario;
  CheckMode mode;
  Verdict verdict = Verdict::kPass;
  std::string detail;
  std::vector<SearchRecord> searches;  // empty: no search of this run applies to the cell
  bool as_expected = true;
  std::string expected;      // the accepted verdicts, "a|b"
  std::string history_file;  // of the failing execution, in the results directory
};

// Searches every cell (progress lines on stderr unless quiet, timed from `started`).
std::vector<VerdictCell> run_verdicts(const Options& o, const std::vector<const ScenarioSpec*>& scens,
                                      std::chrono::steady_clock::time_point started);

// The section: a table of the cells, and Paper's duplicate as a readable history (also printed on stdout).
ReportSection verdict_section(const Options& o, const std::vector<VerdictCell>& cells);

}  // namespace frontsteal::model::stealing
