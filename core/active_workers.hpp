// active_workers.hpp — termination detection without a master: the count of workers holding unfinished work.
//
// Invariant (I-T): while any list holds an unclaimed item, or a thief holds a share it has not yet installed,
// the count is > 0. It starts at P each frame (E4); a worker leaves (A2) only after seeing its own list
// exhausted and finishing every item it claimed; a thief joins (A1) before it shrinks a victim's list, while
// it holds the victim's lock and has seen the list non-empty, and leaves again if its share comes out empty.
// An idle worker that reads 0 (A3) knows every item of the frame has been processed; lists can only be
// refilled by steals, and steals need unclaimed items, so 0 is stable until the next frame re-arms the count.
//
// A thief's view can be stale: it may join after the count already reached 0 (it saw an old Front), in which
// case its share is empty after the re-read and it leaves again. Workers that saw 0 wait at the frame
// boundary for everyone, so such a late join never lets a frame's work leak into the next.
#pragma once

#include <cstdint>

#include "core/labelled_access.hpp"
#include "core/state_home.hpp"

namespace frontsteal {

template <class Backend, class Policy>
class ActiveWorkers {
 public:
  // `home`: where the count lives (state_home.hpp); the default builds it in place. A remote home's count
  // starts as its owner made it: rearm() before the first frame.
  explicit ActiveWorkers(std::uint32_t workers, const HomeOf<Backend>& home = {})
      : count_(atomic_word<Backend>(home, StateWord::kActiveCount, workers)) {}

  void join() noexcept { A::template fetch_add<Site::kActiveJoin>(count_, std::uint32_t{1}); }    // A1
  void leave() noexcept { A::template fetch_sub<Site::kActiveLeave>(count_, std::uint32_t{1}); }  // A2
  [[nodiscard]] bool all_idle() const noexcept {
    return A::template load<Site::kActivePoll>(count_) == 0u;  // A3
  }
  // Diagnostics only (StealingWorkers::debug_state): the count as some recent moment saw it.
  [[nodiscard]] std::uint32_t debug_count() const noexcept { return A::peek(count_); }
  // Only the last worker to arrive at a frame boundary calls this, while every other worker waits.
  void rearm(std::uint32_t workers) noexcept {
    A::template store<Site::kFrameResetActive>(count_, workers);  // E4
  }

 private:
  using A = Access<Backend, Policy>;
  typename Backend::template Atomic<std::uint32_t> count_;
};

}  // namespace frontsteal
