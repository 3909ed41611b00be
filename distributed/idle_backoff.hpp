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
// then 1, 2, 4 ... 256 us.
inline void idle_back_off(std::uint32_t failed, bool yield_first = true) {
  if (failed < 4) {
    if (yield_first) std::this_thread::yield();
    return;
  }
  std::this_thread::sleep_for(std::chrono::microseconds(1u << std::min<std::uint32_t>(failed - 4, 8)));
}

}  // namespace frontsteal::mpi
