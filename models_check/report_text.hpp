// report_text.hpp — the text the Relacy checkers' reports share: the one-cell summary of a search (JSON goes
// through reporting/, nlohmann-json). Free of Relacy (the mains include it; only the suites include Relacy).
#pragma once

#include <string>
#include <string_view>

#include "models_check/search.hpp"

namespace frontsteal::model {

// "100000 it" for a random search; "N done + M discarded" for a tree search (with "capped" if it hit the cap,
// and where it stopped if it found a failure).
inline std::string search_summary(const SearchResult& r) {
  if (r.spin_bound == 0) return std::to_string(r.iterations) + " it" + (r.capped ? " (capped)" : "");
  std::string out = std::to_string(r.completed) + " done + " + std::to_string(r.discarded) + " discarded";
  if (r.capped) out += " (capped)";
  if (r.verdict != Verdict::kPass) out += " (stopped at execution " + std::to_string(r.iterations) + ")";
  return out;
}

}  // namespace frontsteal::model
