// frame_cases.hpp — one frame-level case of frontsteal-stress: a target at P threads for many frames under
// random, skewed item costs, every frame audited (lost = 0 always; duplicates = 0 under an exactly-once contract;
// a negative control must show one). The histogram counts frames with 0, 1 and 2+ duplicates.
#pragma once

#include <cstdint>
#include <string>

#include "core/id_range.hpp"
#include "stress/stress_options.hpp"

namespace frontsteal::stress {

struct TargetInfo;  // stress_targets.hpp

struct CaseResult {
  std::string target;
  std::string contract;
  bool negative_control = false;
  WorkerId threads = 0;
  ItemId items = 0;
  std::uint64_t frames = 0;
  std::uint64_t frames_dup0 = 0, frames_dup1 = 0, frames_dup2plus = 0;
  std::uint64_t lost = 0, duplicated = 0;
  std::uint64_t steals = 0, skipped = 0;
  std::uint64_t chaos = 0;
  double seconds = 0;
  bool passed = true;
  std::string verdict;
  double duplicates_per_million_items() const {
    return frames * items == 0 ? 0.0 : 1e6 * static_cast<double>(duplicated) / (static_cast<double>(frames) * items);
  }
};

// Runs target `t` at `p` threads for --frames frames or --seconds (a negative control: until its first duplicate,
// at most --control-seconds); item costs are multiplied by `cost_scale` (0: trivial items, for --rates).
CaseResult run_case(const TargetInfo& t, WorkerId p, const Options& o, std::uint32_t cost_scale);

// One line on stdout: the histogram, lost items, the duplicate rate and the verdict.
void print_case(const CaseResult& c);

}  // namespace frontsteal::stress
