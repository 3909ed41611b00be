// litmus_catalogue.hpp — the tests the axiomatic checker is validated on, each with its expected verdict and its
// source.
//
// Two kinds of entry. AArch64 tests are checked under ARMv8 alone: transcribed from herd's catalogues
// (herdtools7: catalogue/aarch64/tests and catalogue/aarch64-readers-guide/tests, the programs and the verdicts of
// their kinds.txt), from Maranget, Sarkar and Sewell's ARM/POWER tutorial, and, for the few ordered-before clauses
// no published test isolates, written here with the verdict derived by hand from the clause (their source says
// so). C++ tests (the RC11 paper's examples, the classic shapes with C++ orders, and the fetch_add case of LLVM
// issue #69503) are checked under RC11, RC11 without no-thin-air, and ARMv8 after the standard mapping
// (program.hpp). A verdict is "allowed" when some consistent execution reaches the test's final state.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "models_check/axiomatic/models.hpp"
#include "models_check/axiomatic/program.hpp"

namespace frontsteal::axiomatic {

struct CatalogueEntry {
  LitmusTest test;
  bool is_cpp = false;  // C++ orders (RC11; ARMv8 through compile_to_armv8) or AArch64 instructions (ARMv8 only)
  std::string source;   // where the expected verdicts come from
  // Expected verdict per Model (rc11, rc11_without_nta, armv8): true = allowed; empty = not asked.
  std::array<std::optional<bool>, 3> expected;
};

std::vector<CatalogueEntry> litmus_catalogue();

// The tests of herd's AArch64 kinds.txt that this checker's language cannot express (a compare-and-swap that may
// fail, compares against a loaded value or passes a dependency through its Rs register), named so the report can
// list what is not covered.
std::vector<std::string> untranscribed_aarch64_tests();

}  // namespace frontsteal::axiomatic
