// validation.hpp — the checker against the catalogue: for every entry and every model it has an expected
// verdict for, the verdict found, and whether the two agree. The checker counts only if all agree, and only if
// each planted axiom defect (ModelDefect) makes at least one disagree.
#pragma once

#include <string>
#include <vector>

#include "models_check/axiomatic/checker.hpp"
#include "models_check/axiomatic/litmus_catalogue.hpp"

namespace frontsteal::axiomatic {

struct ValidationRow {
  std::string test;
  std::string source;
  Model model;
  bool expected_allowed;
  bool found_allowed;
  long candidates;
  long consistent;
  std::string witness;  // the execution that reaches the final state, when allowed
  bool agrees() const { return expected_allowed == found_allowed; }
};

inline std::vector<ValidationRow> validate(const std::vector<CatalogueEntry>& catalogue,
                                           ModelDefect defect = ModelDefect::none) {
  std::vector<ValidationRow> rows;
  for (const CatalogueEntry& entry : catalogue) {
    for (const Model model : {Model::rc11, Model::rc11_without_nta, Model::armv8}) {
      const auto& expected = entry.expected[static_cast<int>(model)];
      if (!expected) continue;
      // C++ programs reach ARMv8 through the standard mapping; AArch64 programs are already ARMv8.
      const LitmusTest program = entry.is_cpp && model == Model::armv8 ? compile_to_armv8(entry.test) : entry.test;
      const Verdict v = check(program, model, defect);
      rows.push_back({entry.test.name, entry.source, model, *expected, v.allowed, v.candidates, v.consistent,
                      v.witness ? describe(*v.witness) : std::string{}});
    }
  }
  return rows;
}

}  // namespace frontsteal::axiomatic
