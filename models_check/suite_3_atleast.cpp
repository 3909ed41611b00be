// One Relacy instantiation per file (each costs ~5 s and ~265 MB to compile): 3 threads, atleast check mode.
#include "models_check/protocol_suite.hpp"

namespace frontsteal::model {
SearchResult run_suite_3_atleast(const ScenarioSpec& scenario, const SearchConfig& config) {
  return simulate_suite<ProtocolSuite<3, CheckMode::kAtLeastOnce>>(scenario, config);
}
}  // namespace frontsteal::model
