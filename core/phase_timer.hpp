// phase_timer.hpp — the clock behind the loss account's phase times (frame_stats.hpp: wake, search, steal,
// wait on ListTransient, termination), as a type the frame loop takes as a template parameter.
//
// Why a parameter: the account's extra clock reads sit on the thief's path (when a steal starts, when a wait on
// ListTransient starts and ends, when a search starts), never on the owner's per-item path; NoPhaseTimer
// compiles every one of them away, so the cost of the account can be measured against the same code without it
// (schedulers/registry.hpp lists that variant). The reads the frame loop always made (busy time per drain,
// the worker's span) are not the timer's: utilization is reported either way.
#pragma once

#include <chrono>
#include <cstdint>

namespace frontsteal {

// steady_clock (CLOCK_MONOTONIC through the vDSO on Linux), in nanoseconds: the same clock as the main job's
// harness and every scheduler's busy time, so times taken on different threads can be subtracted.
struct SteadyPhaseTimer {
  static constexpr bool kOn = true;
  static std::int64_t now() noexcept {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
};

// No phase times: every read is the constant 0, so the account's fields stay 0 and cost nothing.
struct NoPhaseTimer {
  static constexpr bool kOn = false;
  static constexpr std::int64_t now() noexcept { return 0; }
};

// The same clock as SteadyPhaseTimer, as a time point's nanoseconds (for reads the frame loop already makes).
inline std::int64_t steady_ns(std::chrono::steady_clock::time_point t) noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace frontsteal
