// modelcheck_mutation.hpp — frontsteal-modelcheck's memory-order mutation: one-step weakenings of a policy run
// against every scenario until one kills them (the kill matrix, every survivor explained), the certificate of
// Minimal (every weakening must be killed), and the greedy derivation of a minimal table. Free of Relacy.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "models_check/checker_report.hpp"
#include "models_check/modelcheck_options.hpp"

namespace frontsteal::model::stealing {

// The kill matrix of o.mutants's weakenings; `all_expected` becomes false for a survivor no reason explains.
ReportSection kill_matrix_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& all_expected,
                                  std::chrono::steady_clock::time_point started);

// Minimal's orders and its weakenings; `certified`: every one was killed.
ReportSection certificate_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& certified,
                                  std::chrono::steady_clock::time_point started);

// Greedy: weaken one site one step at a time, keeping each weakening under which every scenario still passes.
PolicyTable derive_minimal(const PolicyTable& base, const std::vector<const ScenarioSpec*>& scens, const Options& o);

// "  O1 owner.announce: seq_cst" per stealing-protocol site, one line each.
std::string describe_table(const PolicyTable& t);

}  // namespace frontsteal::model::stealing
