// publication_check.hpp — the publication model checker's interface, free of Relacy (publication_suite.cpp
// implements it): run one publication scenario under current_table() and get a verdict.
#pragma once

#include "models_check/publication_scenarios.hpp"
#include "models_check/search.hpp"

namespace frontsteal::model {

SearchResult run_publication(const PublicationSpec& spec, const SearchConfig& config);

}  // namespace frontsteal::model
