// One Relacy instantiation per file (each costs ~5 s and ~265 MB to compile): 2 threads, exact check mode.
#include "models_check/protocol_suite.hpp"

namespace frontsteal::model {
SearchResult run_suite_2_exact(const ScenarioSpec& scenario, const SearchConfig& config) {
  return simulate_suite<ProtocolSuite<2, CheckMode::kExactlyOnce>>(scenario, config);
}
}  // namespace frontsteal::model
