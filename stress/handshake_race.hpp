// handshake_race.hpp — the ListTransient handshake raced head-on, round after round, on real hardware.
//
// Frame-level stress rarely lines a steal up with a claim to the nanosecond, so it says little about how
// often the store->load reordering of x86 actually bites. Here two threads meet at a barrier every round:
// the owner installs a list of `items` ids and claims them one by one, doing `work_per_item` multiply-adds
// after each claim; the thief, released at the same
// moment, makes one steal attempt on that list. After the round the owner's claims are compared with the
// thief's kept share: an id in both is a duplicate. No chaos, no sanitizer: release builds only.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "core/frame_loop.hpp"
#include "core/std_backend.hpp"
#include "stress/watchdog.hpp"

namespace frontsteal::stress {

struct HandshakeRaceResult {
  std::uint64_t rounds = 0;
  std::uint64_t steals_kept = 0;  // rounds in which the thief kept a non-empty share
  std::uint64_t skipped = 0;      // items the thief dropped after its re-read of Front
  std::uint64_t duplicates = 0;   // items claimed by the owner and kept by the thief in the same round
  std::uint64_t rounds_with_duplicates = 0;
  double seconds = 0;
  double duplicates_per_million_rounds() const { return rounds ? 1e6 * duplicates / static_cast<double>(rounds) : 0; }
};

template <class Policy, class Backend = StdBackend>
HandshakeRaceResult race_handshake(std::uint64_t rounds, ItemId items, std::uint32_t work_per_item,
                                   double max_seconds) {
  StealingWorkers<Backend, Policy> core(2, items, 1);
  auto& owner = core.owner(0);
  auto& thief = core.thief(1);
  auto& slot = core.slot(0);
  const RangeList list{{0, items}};

  std::atomic<std::uint64_t> go{0};    // round number released by the owner after installing
  std::atomic<std::uint64_t> done{0};  // round number the thief has finished
  std::atomic<bool> stop{false};
  std::vector<std::uint8_t> kept_by_thief(items, 0);
  HandshakeRaceResult r;

  std::thread thief_thread([&] {
    for (std::uint64_t round = 1;; ++round) {
      while (go.load(std::memory_order::acquire) < round) {
        if (stop.load(std::memory_order::relaxed)) return;
        Backend::spin_pause(Site::kCount, 0);
      }
      const StealOutcome outcome = thief.try_steal(slot);
      if (outcome == StealOutcome::kStolen) {
        for (const IdRange& range : thief.share()) {
          for (ItemId i = range.begin; i < range.end; ++i) kept_by_thief[i] = 1;
        }
        ++r.steals_kept;
      }
      if (outcome == StealOutcome::kStolen || outcome == StealOutcome::kSkippedAll) r.skipped += thief.skipped();
      done.store(round, std::memory_order::release);
    }
  });

  // No frames here, so the watchdog's default probe (busy while a frame is in flight) does not apply: the race
  // is always busy, and its progress is the slot's state plus the rounds both sides have finished. A thief
  // stuck at T4 freezes both.
  const Watchdog dog(
      std::string("frontsteal-stress --rates: handshake race, ") + std::string(Policy::kName),
      [&] {
        return WatchdogSample{true, core.debug_state().fingerprint() ^ (go.load(std::memory_order::relaxed) << 20) ^
                                        done.load(std::memory_order::relaxed)};
      },
      [&](std::FILE* out) {
        std::fprintf(out, "  round %llu released, %llu finished by the thief (worker 0 owns, worker 1 steals)\n",
                     static_cast<unsigned long long>(go.load(std::memory_order::relaxed)),
                     static_cast<unsigned long long>(done.load(std::memory_order::relaxed)));
        core.debug_state().print(out);
      });
  std::vector<std::uint8_t> claimed(items, 0);
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t round = 1; round <= rounds; ++round) {
    owner.install(list);
    go.store(round, std::memory_order::release);
    while (const auto id = owner.try_claim()) {
      claimed[*id] = 1;
      // A little work per item keeps the owner claiming when the thief arrives (its wake-up costs ~100 ns).
      std::uint32_t x = work_per_item;
      for (std::uint32_t i = 0; i < work_per_item; ++i) {
        x = x * 1664525u + 1013904223u;
        asm volatile("" : "+r"(x));
      }
    }
    while (done.load(std::memory_order::acquire) < round) Backend::spin_pause(Site::kCount, 0);
    std::uint64_t dup = 0;
    for (ItemId i = 0; i < items; ++i) {
      dup += claimed[i] & kept_by_thief[i];
      claimed[i] = kept_by_thief[i] = 0;
    }
    r.duplicates += dup;
    r.rounds_with_duplicates += dup ? 1 : 0;
    r.rounds = round;
    if ((round & 1023) == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > max_seconds) {
      break;
    }
  }
  stop.store(true);
  thief_thread.join();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace frontsteal::stress
