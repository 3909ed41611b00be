// chaselev_scenarios.hpp — the Chase–Lev deque's model-checking scenarios, as data (chaselev_suite.cpp runs them).
//
// Thread 0 is the owner: it runs `owner_ops` in order, 'P' pushing the next item (0, 1, 2, …) and 'T' taking one.
// Threads 1.. are thieves: each calls steal() `steal_attempts` times (a lost race counts as an attempt), so every
// scenario is a finite program and a tree search over it ends. After the threads, the harness drains the deque
// with take(): every item pushed must have come out exactly once.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace frontsteal::model {

struct ChaseLevSpec {
  std::string_view name;
  std::string_view checks;       // one line: the race this scenario exists for
  std::uint32_t capacity;        // power of two
  std::string_view owner_ops;    // 'P' push the next item, 'T' take
  std::uint32_t thieves;         // 1 or 2
  std::uint32_t steal_attempts;  // per thief
};

inline constexpr std::uint32_t kMaxChaseLevItems = 8;

inline const std::vector<ChaseLevSpec>& chaselev_scenarios() {
  static const std::vector<ChaseLevSpec> all{
      {"owner_vs_thief",
       "owner pushes 3 and takes, one thief steals twice; capacity 2, so push wraps onto slots a thief may read", 2,
       "PPTPT", 1, 2},
      {"owner_vs_two_thieves",
       "two elements, two thieves with one steal each against the owner's take: the store-buffering handshake", 4,
       "PPT", 2, 1},
      {"last_element", "one element: the owner's take (CAS K6) against one thief's steal (CAS S5)", 2, "PT", 1, 1},
  };
  return all;
}

}  // namespace frontsteal::model
