// One Relacy instantiation per file (each costs ~5 s and ~265 MB to compile): 3 threads, exact check mode.
#include "models_check/protocol_suite.hpp"

namespace frontsteal::model {
SearchResult run_suite_3_exact(const ScenarioSpec& scenario, const SearchConfig& config) {
  return simulate_suite<ProtocolSuite<3, CheckMode::kExactlyOnce>>(scenario, config);
}
}  // namespace frontsteal::model
