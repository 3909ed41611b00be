// synthetic_work.hpp — busy work the optimizer cannot remove, for synthetic workloads and tests.
#pragma once

#include <cstdint>

namespace frontsteal {

// About `iterations` dependent multiply-adds (roughly 1 ns each on current x86).
inline void spin_work(std::uint32_t iterations) noexcept {
  std::uint32_t x = iterations;
  for (std::uint32_t i = 0; i < iterations; ++i) {
    x = x * 1664525u + 1013904223u;
    asm volatile("" : "+r"(x));
  }
}

}  // namespace frontsteal
