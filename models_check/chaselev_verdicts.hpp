// chaselev_verdicts.hpp — frontsteal-modelcheck-chaselev's two tables: the verdicts of Lê et al.'s orders
// (ChaseLev, must pass) and of three planted defects (each must fail) on every scenario of
// chaselev_scenarios.hpp, and the kill matrix of every one-step weakening of ChaseLev (a survivor must be
// listed in chaselev_survivors.hpp). Free of Relacy (chaselev_suite.cpp runs the searches).
#pragma once

#include "models_check/checker_options.hpp"
#include "reporting/table.hpp"

namespace frontsteal::model::chaselev {

inline constexpr const char* kProgram = "frontsteal-modelcheck-chaselev";

// Per policy and scenario: the random search, the context-bound search (budget.bound > 0) and the full search
// (budget.full); histories of failing executions under budget.out/histories/. `ok` becomes false on any
// verdict that is not as expected.
report::Table verdict_table(const SearchBudget& budget, bool& ok);

// Per mutant: the random search of every scenario, then (budget.bound > 0) the context-bound one, up to the
// first kill. `ok` becomes false for a survivor that is not listed or a listed one that is killed.
report::Table kill_table(const SearchBudget& budget, bool& ok);

}  // namespace frontsteal::model::chaselev
