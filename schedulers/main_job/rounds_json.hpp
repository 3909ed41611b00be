// rounds_json.hpp — an arm's per-round record (measure::ArmRounds) in frontsteal.json and back: the main job
// writes it, frontsteal-calibration-summary and frontsteal-compare read it, so the three agree on one format
// {round[], ms[], probe_ns_per_million_steps[], segment[], instance[]} (docs/results-schema.md).
#pragma once

#include <cstddef>

#include "measure/paired_analysis.hpp"
#include "reporting/json.hpp"

namespace frontsteal::main_job {

inline report::Json rounds_json(const measure::ArmRounds& r) {
  return {{"round", r.round},
          {"ms", r.time},
          {"probe_ns_per_million_steps", r.probe},
          {"segment", r.block},
          {"instance", r.instance}};
}

// Throws what nlohmann::json throws for a missing key or a wrong type. Files without round ids (written before
// rounds held one P) count one round per entry, in order; files without instance ids (one instance per run)
// leave them -1, which the analysis reads as independent rounds.
inline measure::ArmRounds rounds_from_json(const report::Json& j) {
  measure::ArmRounds r;
  const auto& ms = j.at("ms");
  const auto& probe = j.at("probe_ns_per_million_steps");
  const auto& segment = j.at("segment");
  const bool ids = j.contains("round"), instances = j.contains("instance");
  for (std::size_t k = 0; k < ms.size(); ++k) {
    r.add(ids ? j.at("round")[k].get<std::size_t>() : k, ms[k].get<double>(), probe[k].get<double>(),
          segment[k].get<int>(), instances ? j.at("instance")[k].get<int>() : -1);
  }
  return r;
}

}  // namespace frontsteal::main_job
