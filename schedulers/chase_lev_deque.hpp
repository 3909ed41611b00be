// chase_lev_deque.hpp — the Chase–Lev work-stealing deque with the C11 memory orders proven correct by
// Lê, Pop, Cohen & Zappa Nardelli, "Correct and Efficient Work-Stealing for Weak Memory Models" (PPoPP'13,
// Fig. 1). Written from the paper's pseudo-code.
//
// ROLES
//   owner    push(x) and take(): the bottom end (LIFO)
//   thieves  steal(): the top end (FIFO); any number, concurrently
// OWNERSHIP
//   bottom_  written by the owner only; read by thieves
//   top_     advanced by CAS (thieves, and the owner when it takes the last element)
//   buffer_  slot b written by the owner in push before bottom_ passes it; read by owner and thieves
// INVARIANTS
//   top_ <= bottom_ + 1 at all times; the elements are buffer_[top_ .. bottom_). Capacity is fixed (a power of
//   two): push on a full deque returns false (the Chase–Lev resize is not needed by our users, whose
//   occupancy is bounded by the depth of a binary range split, see chase_lev_scheduler.hpp).
// LINEARIZATION POINTS
//   push: the store to bottom_;  take: the store of bottom_ − 1 when t < b, else the CAS on top_;
//   steal: the CAS on top_.
// ORDERS (labels as in Lê et al.)
//   push   P1 top_ acquire; P2 buffer relaxed; P3 release fence; P4 bottom_ relaxed.
//          P3 -> S3: a thief that reads the new bottom_ reads the element written before it.
//   take   T1 bottom_ relaxed; T2 bottom_ := b relaxed; T3 seq_cst fence; T4 top_ relaxed;
//          T5 CAS top_ seq_cst (last element). T3 against S2: the Dekker pair — the owner's store to
//          bottom_ and a thief's store to top_ cannot both be missed by the other's later load.
//   steal  S1 top_ acquire; S2 seq_cst fence; S3 bottom_ acquire; S4 buffer relaxed; S5 CAS top_ seq_cst.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <type_traits>

namespace frontsteal::sched {

enum class StealResult { kSuccess, kEmpty, kLostRace };

template <class T>
class ChaseLevDeque {
  static_assert(std::is_trivially_copyable_v<T> && std::atomic<T>::is_always_lock_free);

 public:
  explicit ChaseLevDeque(std::size_t capacity_power_of_two = 64)
      : mask_(capacity_power_of_two - 1), buffer_(std::make_unique<std::atomic<T>[]>(capacity_power_of_two)) {}

  // Owner only. False when full.
  bool push(T x) {
    const std::int64_t b = bottom_.load(std::memory_order::relaxed);
    const std::int64_t t = top_.load(std::memory_order::acquire);  // P1
    if (b - t > static_cast<std::int64_t>(mask_)) return false;
    buffer_[b & mask_].store(x, std::memory_order::relaxed);        // P2
    std::atomic_thread_fence(std::memory_order::release);          // P3
    bottom_.store(b + 1, std::memory_order::relaxed);               // P4
    return true;
  }

  // Owner only. False when empty.
  bool take(T& out) {
    const std::int64_t b = bottom_.load(std::memory_order::relaxed) - 1;  // T1
    bottom_.store(b, std::memory_order::relaxed);                           // T2
    std::atomic_thread_fence(std::memory_order::seq_cst);                   // T3
    std::int64_t t = top_.load(std::memory_order::relaxed);                 // T4
    if (t > b) {
      bottom_.store(b + 1, std::memory_order::relaxed);
      return false;
    }
    out = buffer_[b & mask_].load(std::memory_order::relaxed);
    if (t < b) return true;
    // The last element: race the thieves for it.
    const bool won = top_.compare_exchange_strong(t, t + 1, std::memory_order::seq_cst,
                                                  std::memory_order::relaxed);  // T5
    bottom_.store(b + 1, std::memory_order::relaxed);
    return won;
  }

  // Any thread.
  StealResult steal(T& out) {
    std::int64_t t = top_.load(std::memory_order::acquire);              // S1
    std::atomic_thread_fence(std::memory_order::seq_cst);                // S2
    const std::int64_t b = bottom_.load(std::memory_order::acquire);     // S3
    if (t >= b) return StealResult::kEmpty;
    out = buffer_[t & mask_].load(std::memory_order::relaxed);           // S4
    if (!top_.compare_exchange_strong(t, t + 1, std::memory_order::seq_cst, std::memory_order::relaxed)) {  // S5
      return StealResult::kLostRace;
    }
    return StealResult::kSuccess;
  }

  // Racy size, for statistics and tests.
  std::int64_t size_hint() const noexcept {
    return bottom_.load(std::memory_order::relaxed) - top_.load(std::memory_order::relaxed);
  }

 private:
  alignas(64) std::atomic<std::int64_t> top_{0};
  alignas(64) std::atomic<std::int64_t> bottom_{0};
  std::size_t mask_;
  std::unique_ptr<std::atomic<T>[]> buffer_;
};

}  // namespace frontsteal::sched
