// Dispatches a scenario to the suite instantiation with its thread count and check mode.
#include <stdexcept>
#include <string>

#include "models_check/search.hpp"

namespace frontsteal::model {

SearchResult run_suite_2_exact(const ScenarioSpec&, const SearchConfig&);
SearchResult run_suite_2_atleast(const ScenarioSpec&, const SearchConfig&);
SearchResult run_suite_3_exact(const ScenarioSpec&, const SearchConfig&);
SearchResult run_suite_3_atleast(const ScenarioSpec&, const SearchConfig&);

SearchResult run_scenario(const ScenarioSpec& scenario, CheckMode mode, const SearchConfig& config) {
  const bool exact = mode == CheckMode::kExactlyOnce;
  switch (scenario.threads()) {
    case 2: return exact ? run_suite_2_exact(scenario, config) : run_suite_2_atleast(scenario, config);
    case 3: return exact ? run_suite_3_exact(scenario, config) : run_suite_3_atleast(scenario, config);
    default:
      throw std::invalid_argument("scenario " + std::string(scenario.name) + " needs " +
                                  std::to_string(scenario.threads()) + " threads; suites exist for 2 and 3");
  }
}

}  // namespace frontsteal::model
