// round_order.hpp — the order in which the arms of one round run.
//
// A fixed order lets a steady drift of the machine's speed bias one arm against another: the arm that always
// runs later in the round always sees the later, slower (or faster) machine. Randomizing the order in every
// round (Abedi & Brecht, ICPE 2017: "randomized multiple interleaved trials"; Google Benchmark's random
// interleaving) turns that bias into noise that the paired interval accounts for. Counterbalancing (A-B-B-A:
// every other round reversed) is the deterministic alternative; the fixed order is kept as a negative control
// (tests/measure/round_order_test.cpp shows its bias on a drifting series, and randomization removing it).
//
// The generator is splitmix64 (measure/paired_comparison.hpp), seeded by (seed, round): the same seed gives
// the same orders on every platform, and any round's order can be recomputed on its own.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "measure/paired_comparison.hpp"

namespace frontsteal::measure {

enum class OrderKind { kRandom, kCounterbalanced, kFixed };

inline const char* to_string(OrderKind k) noexcept {
  switch (k) {
    case OrderKind::kRandom: return "random";
    case OrderKind::kCounterbalanced: return "counterbalanced";
    case OrderKind::kFixed: return "fixed";
  }
  return "?";
}

inline std::optional<OrderKind> order_kind_named(const std::string& s) {
  if (s == "random") return OrderKind::kRandom;
  if (s == "counterbalanced") return OrderKind::kCounterbalanced;
  if (s == "fixed") return OrderKind::kFixed;
  return std::nullopt;
}

// The order of `arms` arms (indices 0 .. arms-1) in round `round`.
inline std::vector<std::size_t> round_order(std::size_t arms, std::uint64_t seed, std::size_t round, OrderKind kind) {
  std::vector<std::size_t> order(arms);
  std::iota(order.begin(), order.end(), std::size_t{0});
  switch (kind) {
    case OrderKind::kFixed: break;
    case OrderKind::kCounterbalanced:
      if (round % 2 == 1) std::reverse(order.begin(), order.end());
      break;
    case OrderKind::kRandom: {
      // Fisher-Yates with a generator of its own per round: round k's order does not depend on how many draws
      // earlier rounds made.
      stats::SplitMix64 rng(seed ^ (0x9e37'79b9'7f4a'7c15ull * (round + 1)));
      for (std::size_t i = arms; i > 1; --i) std::swap(order[i - 1], order[rng.index(i)]);
      break;
    }
  }
  return order;
}

}  // namespace frontsteal::measure
