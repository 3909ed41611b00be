// One Relacy instantiation per file (each costs ~5 s and ~265 MB to compile): 2 threads, atleast check mode.
#include "models_check/protocol_suite.hpp"

namespace frontsteal::model {
SearchResult run_suite_2_atleast(const ScenarioSpec& scenario, const SearchConfig& config) {
  return simulate_suite<ProtocolSuite<2, CheckMode::kAtLeastOnce>>(scenario, config);
}
}  // namespace frontsteal::model
