// thread_cpu_time.hpp — the calling thread's CPU time (CLOCK_THREAD_CPUTIME_ID), for telling a worker that
// the OS descheduled apart from one that sat idle for lack of work.
//
// A worker's part of a frame lasts `active` wall time; of that it spends `busy` processing items and `cpu`
// on a CPU. Idle workers spin (they look for work), so active − cpu is time the thread wanted a CPU and did
// not have one (descheduled, or asleep on a contended lock), while active − busy is time without items.
// The clock is a system call on Linux (no vDSO fast path for thread clocks, ~0.1–0.5 µs), so schedulers read
// it once per worker per frame, never per item.
#pragma once

#include <cstdint>
#include <ctime>

namespace frontsteal {

// CPU time consumed by the calling thread, in nanoseconds; 0 if the clock is unavailable.
inline std::int64_t thread_cpu_ns() noexcept {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0;
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace frontsteal
