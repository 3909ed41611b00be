// chaselev_check.hpp — the Chase–Lev model checker's interface, free of Relacy (chaselev_suite.cpp implements it):
// run one deque scenario under current_table() with one search and get a verdict.
#pragma once

#include "models_check/chaselev_scenarios.hpp"
#include "models_check/search.hpp"

namespace frontsteal::model {

SearchResult run_chaselev(const ChaseLevSpec& spec, const SearchConfig& config);

}  // namespace frontsteal::model
