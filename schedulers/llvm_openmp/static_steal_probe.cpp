// static_steal_probe.cpp — the static_steal probe and its range arithmetic (static_steal_probe.hpp).
#include "schedulers/llvm_openmp/static_steal_probe.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace frontsteal::llvm_openmp {

using Clock = std::chrono::steady_clock;

long long range_start(long long t, long long chunks, long long threads) {
  const long long small = chunks / threads, extras = chunks % threads;
  return t * small + std::min(t, extras);
}

int owner_of(long long c, long long chunks, long long threads) {
  int t = static_cast<int>(std::min(threads - 1, c / std::max(1LL, chunks / threads)));
  while (t > 0 && range_start(t, chunks, threads) > c) --t;
  while (t + 1 < threads && range_start(t + 1, chunks, threads) <= c) ++t;
  return t;
}

// (a) and (b) of the header, in the loop body.
int probe_static_steal(int threads) {
  if (threads == 1) return 1;  // one thread: nothing to tell apart
  const long long m = 64LL * threads;
  for (int attempt = 1; attempt <= 5; ++attempt) {
    std::vector<long long> first(static_cast<std::size_t>(threads), -1);
    std::atomic<int> arrived{0};
    std::atomic<bool> absent{false}, stolen{false}, no_steal{false};
#pragma omp parallel num_threads(threads)
    {
      const int t = omp_get_thread_num();
#pragma omp for schedule(runtime) nowait
      for (int i = 0; i < static_cast<int>(m); ++i) {  // 32-bit, as the frames' loop
        if (owner_of(i, m, threads) != t) stolen = true;
        if (first[static_cast<std::size_t>(t)] >= 0) continue;
        first[static_cast<std::size_t>(t)] = i;
        arrived.fetch_add(1);
        auto deadline = Clock::now() + std::chrono::seconds(10);
        while (arrived.load() < threads) {  // (a)
          if (Clock::now() > deadline) {
            absent = true;
            break;
          }
          std::this_thread::yield();
        }
        deadline = Clock::now() + std::chrono::seconds(10);
        while (t == 0 && !absent && !stolen) {  // (b)
          if (Clock::now() > deadline) {
            no_steal = true;
            break;
          }
          std::this_thread::yield();
        }
      }
    }
    if (absent) continue;
    bool ranges = true;
    for (int t = 0; t < threads; ++t)
      ranges = ranges && first[static_cast<std::size_t>(t)] == range_start(t, m, threads);
    return ranges && stolen && !no_steal ? attempt : 0;
  }
  return 0;
}

}  // namespace frontsteal::llvm_openmp
