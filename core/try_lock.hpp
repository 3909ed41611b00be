// try_lock.hpp — LockList[p]: the non-blocking try-lock that serializes thieves of one victim.
//
// Paper §4.2.1 line 62: "Non-blocking lock ensures that if p_i cannot acquire LockList[p_b], there must exist
// another idle processor p_j currently sharing ActivityList[p_b]". A thief never waits for it: a failed
// try_lock moves the thief to its next victim. The owner of the list takes it only while idle, to install a
// new list (lock_spinning), which is why no owner *claim* ever waits on it.
//
// Orders: L2 (acquire) pairs with L3 (release) of the previous holder, so whatever a holder wrote to the
// slot's End and list body is visible to the next holder. L1 is only a hint that saves an exchange: on a
// cache-coherent machine a load of a held lock leaves its line shared where an exchange would take it. A backend
// on which every access is a round trip (one-sided operations: distributed/rma_backend.hpp) declares
// `static constexpr bool kSkipLockProbe = true;` and tries L2 at once; L2's result alone decides either way.
#pragma once

#include <cstdint>

#include "core/labelled_access.hpp"
#include "core/state_home.hpp"

namespace frontsteal {

// Whether try_lock probes with L1 before L2 (every backend but those that declare kSkipLockProbe).
template <class Backend>
inline constexpr bool kProbesLock = !requires {
  requires Backend::kSkipLockProbe;
};

template <class Backend, class Policy>
class TryLock {
 public:
  // `home`: where the lock word lives (state_home.hpp); the default builds it in place, unlocked.
  explicit TryLock(const HomeOf<Backend>& home = {}) : held_(atomic_word<Backend>(home, StateWord::kLock, 0u)) {}
  TryLock(const TryLock&) = delete;
  TryLock& operator=(const TryLock&) = delete;

  [[nodiscard]] bool try_lock() noexcept {
    if constexpr (kProbesLock<Backend>) {
      if (A::template load<Site::kLockProbe>(held_) != 0u) return false;  // L1
    }
    return A::template exchange<Site::kLockAcquire>(held_, std::uint32_t{1}) == 0u;  // L2
  }

  // Only for the owner of the list, when idle: the holders are thieves that finish in a bounded number of
  // their own steps (their only wait is on this idle owner's ListTransient, which is 0).
  void lock_spinning() noexcept {
    for (std::uint32_t spins = 0; !try_lock(); ++spins) Backend::spin_pause(Site::kLockProbe, spins);
  }

  // Diagnostics only (StealingWorkers::debug_state): whether someone held the lock at some recent moment.
  [[nodiscard]] bool debug_held() const noexcept { return A::peek(held_) != 0u; }

  void unlock() noexcept { A::template store<Site::kLockRelease>(held_, std::uint32_t{0}); }  // L3

 private:
  using A = Access<Backend, Policy>;
  typename Backend::template Atomic<std::uint32_t> held_;
};

}  // namespace frontsteal
