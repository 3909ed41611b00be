// idle_backoff.hpp — the pause of an idle rank or worker after fruitless rounds of steal attempts or requests.
//
// With more ranks (or threads) than cores an idle thief's polling takes the CPU from the very owner it waits for,
// so after the first few fruitless rounds it sleeps, doubling up to 256 us. The same schedule is modelled by the
// simulator (rma_simulator.cpp's backoff).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <thread>

namespace frontsteal::mpi {

// The pause after `failed` fruitless rounds in a row (counting this one): below 4 a yield (with `yield_first`),
// then 1, 2, 4 ... up to `cap_us` (256 us).
inline void idle_back_off(std::uint32_t failed, bool yield_first = true, std::uint32_t cap_us = 256) {
  if (failed < 4) {
    if (yield_first) std::this_thread::yield();
    return;
  }
  std::this_thread::sleep_for(
      std::chrono::microseconds(std::min<std::uint32_t>(1u << std::min<std::uint32_t>(failed - 4, 8), cap_us)));
}

// A rank waiting on its lifelines (lifelines.hpp) polls only its own window words: it backs off to at most this,
// so that an invitation or the frame's end is seen within a few us.
inline constexpr std::uint32_t kLifelineWaitCapUs = 8;

// hier: a worker other than a rank's main thread looks for a sibling's chunk to halve; a chunk is about
// `chunk_us` of work, so sleeping longer than an eighth of one misses most of the half it could take (SIMULATED
// at 256 ranks x 16 threads, docs/mpi.md). The cap: the largest power of two us <= chunk_us / 8, at least 1.
inline std::uint32_t sibling_backoff_cap_us(double chunk_us) {
  std::uint32_t cap = 1;
  while (cap < 256 && 2.0 * cap <= chunk_us / 8) cap *= 2;
  return cap;
}

}  // namespace frontsteal::mpi
