// stress_report.hpp — everything one run of frontsteal-stress found, and how it is written: stress.{md,json} for
// the bounded suite, rates.{md,json} for --rates, one report::Table per section (handshake races, frame-level
// cases, the model checker's scenarios on real threads, faults) rendered to markdown and JSON.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stress/fault_scenarios.hpp"
#include "stress/frame_cases.hpp"
#include "stress/handshake_race.hpp"
#include "stress/stress_options.hpp"

namespace frontsteal::stress {

struct ScenarioRow {
  std::string target;
  std::string scenario;
  std::uint64_t runs = 0;
  std::uint64_t lost = 0;
  std::uint64_t duplicated = 0;
  bool passed = true;
};

struct RaceRow {
  std::string policy;
  HandshakeRaceResult result;
};

// Everything a run found: the frame-level cases, the handshake races (--rates), the scenarios and the faults.
struct StressReport {
  std::vector<CaseResult> cases;
  std::vector<FaultResult> faults;
  std::vector<RaceRow> races;
  std::vector<ScenarioRow> scenario_rows;
  bool all_ok = true;
};

// Writes the markdown and JSON files into o.out; throws std::runtime_error naming a file it cannot write.
void write_results(const Options& o, const StressReport& r, double seconds);

}  // namespace frontsteal::stress
