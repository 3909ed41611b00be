// litmus_agreement.hpp — the explorer validated against the axiomatic checker (models_check/axiomatic/): a litmus
// program run as code (litmus_program.hpp) must have exactly the consistent executions the checker enumerates
// for it, each explored once, and reach its final state exactly when the checker allows it.
//
// Like with like: the explorer explores executions with po ∪ rf acyclic and assumes no dependency, so the checker
// is asked the same question: the program without its dependencies (ARMv8 through the mapping the explorer uses,
// no ST<OP> forms), under RC11, or under ARMv8 restricted to executions with po ∪ rf acyclic.
#pragma once

#include <string>
#include <vector>

#include "models_check/axiomatic/checker.hpp"
#include "models_check/graph/explorer.hpp"
#include "models_check/graph/litmus_program.hpp"

namespace frontsteal::graph {

struct LitmusAgreement {
  std::string name;
  GraphModel model = GraphModel::rc11;
  long checker_executions = 0;  // consistent candidates (po ∪ rf acyclic)
  bool checker_allowed = false;
  std::uint64_t explored = 0, distinct = 0;
  bool explorer_allowed = false;
  bool agrees() const {
    return static_cast<long>(distinct) == checker_executions && explorer_allowed == checker_allowed;
  }
};

inline ax::LitmusTest without_dependencies(ax::LitmusTest t) {
  for (auto& thread : t.threads) {
    for (auto& in : thread) in.addr_from = in.data_from = in.ctrl_from = -1;
  }
  return t;
}

inline LitmusAgreement compare_with_checker(const ax::LitmusTest& test, GraphModel model,
                                            ExplorerDefect defect = ExplorerDefect::none) {
  LitmusAgreement a;
  a.name = test.name;
  a.model = model;
  ax::LitmusTest asked = without_dependencies(test);
  if (model != GraphModel::rc11) asked = ax::compile_to_armv8(asked, false, model == GraphModel::armv8_ldapr);
  ax::for_each_candidate(asked, [&](const ax::Execution& x) {
    const bool ok =
        model == GraphModel::rc11 ? ax::rc11_consistent(x, true) : ax::armv8_consistent(x) && (x.po | x.rf).acyclic();
    if (ok) {
      ++a.checker_executions;
      a.checker_allowed = a.checker_allowed || ax::reaches(x, asked.final_state);
    }
    return true;
  });
  LitmusProgram program(test);
  ExploreOptions options;
  options.model = model;
  options.stop_at_failure = false;
  options.defect = defect;
  const ExploreResult r = explore(program, options);
  a.explored = r.complete;
  a.distinct = r.distinct;
  a.explorer_allowed = r.outcome.verdict != Verdict::kPass;
  return a;
}

}  // namespace frontsteal::graph
