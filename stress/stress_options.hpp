// stress_options.hpp — what one run of frontsteal-stress does (parsed in stress_main.cpp, through reporting/'s
// CLI11 wrapper; --help gives each option's meaning and default).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::stress {

inline constexpr const char* kProgram = "frontsteal-stress";

struct Options {
  double seconds = 3;                // per case (0 frames: the time bound)
  std::uint64_t frames = 0;          // per case instead of a time bound
  double control_seconds = 60;       // a negative control runs until caught, at most this long
  ItemId items = 256;                // per frame
  std::uint32_t chaos = 2000;        // injections per million labelled accesses
  std::vector<std::string> targets;  // empty or "all": every target, then the scenarios and faults
  std::vector<WorkerId> threads{2, 4, 8};
  std::uint64_t seed = 1;
  std::string out = "out/stress";
  bool rates = false;  // --rates: duplicate rates instead of the bounded suite
  std::uint64_t scenario_runs = 200;
  std::uint64_t rounds = 1000000;  // handshake-race rounds per policy (--rates)
  ItemId race_items = 2;
  std::uint32_t race_work = 50;
  bool quiet = false;
};

}  // namespace frontsteal::stress
