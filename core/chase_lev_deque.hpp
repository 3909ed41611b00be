// chase_lev_deque.hpp — the Chase–Lev work-stealing deque (Chase & Lev, SPAA'05) with the C11 memory orders of
// Lê, Pop, Cohen & Zappa Nardelli, "Correct and Efficient Work-Stealing for Weak Memory Models" (PPoPP'13,
// Fig. 1), written from the paper's pseudo-code behind the project's atomics seam: every shared access is one
// labelled site (site.hpp, Protocol::kChaseLev) whose order comes from a policy (chase_lev_policies.hpp), so the
// same source runs on std::atomic (the baseline scheduler), under chaos (stress/) and in Relacy (models_check/).
//
// ROLES
//   owner    push(x) and take(): the bottom end (LIFO). Exactly one thread at a time.
//   thieves  steal(): the top end (FIFO); any number of threads, concurrently with the owner and each other.
// OWNERSHIP
//   bottom_  written by the owner only (B5, K2, K7, K8); read by thieves (S3)
//   top_     only ever advanced, by a CAS (a thief's S5, or the owner's K6 for the last element)
//   buffer_  slot b % capacity is written by the owner in push (B3) before bottom_ passes b; read by the owner
//            (K5) and by thieves (S4). A slot is atomic (relaxed) because a thief that will lose its CAS may read
//            it while the owner rewrites it after wrapping around: a race on the slot that is harmless only
//            because that thief then discards what it read.
// INVARIANTS
//   top_ <= bottom_ + 1 at all times (bottom_ = top_ - 1 only inside take, between K2 and K7/K8); the elements
//   are buffer_[top_ .. bottom_). Indices are signed 64-bit: on an empty deque K2 makes bottom_ = top_ - 1, which
//   an unsigned index would wrap to a huge "full" deque. Capacity is fixed (a power of two): push on a full deque
//   returns false. The Chase–Lev resize is left out on purpose (our users' occupancy is bounded by the depth of a
//   binary range split, see schedulers/chase_lev_scheduler.hpp), and with it the one published bug of the
//   paper's code (see ERRATUM below).
// LINEARIZATION POINTS
//   push: B5 (bottom_ := b + 1);  take: K2 when it finds t < b, else K6 (the CAS) for the last element, else K4
//   (empty);  steal: S5 when the CAS succeeds, S3 when it finds the deque empty.
// LABELLED ORDERS (ChaseLevOrders; Lê et al.'s label in parentheses)
//   push   B1 read bottom relaxed; B2 (P1) read top acquire; B3 (P2) buffer[b] := x relaxed;
//          B4 (P3) release fence; B5 (P4) bottom := b + 1 relaxed.
//          B4 -> S3: a thief that reads the new bottom reads the element, and everything the owner wrote before
//          pushing it. B2 acquire <- S5: a slot is rewritten only after the thief that emptied it read it.
//   take   K1 (T1) read bottom relaxed; K2 (T2) bottom := b - 1 relaxed; K3 (T3) seq_cst fence;
//          K4 (T4) read top relaxed; K5 read buffer[b] relaxed; K6 (T5) CAS top seq_cst (last element only);
//          K7/K8 bottom := b + 1 relaxed (empty / after the last-element race).
//   steal  S1 read top acquire; S2 seq_cst fence; S3 read bottom acquire; S4 read buffer[t] relaxed;
//          S5 CAS top t -> t + 1 seq_cst.
//   Why K3 and S2 (the handshake). With two elements [x0, x1] (top 0, bottom 2), a thief steals x0 (top 1) and
//   then, in a second steal (or a second thief), reads top 1 (S1) and bottom (S3); the owner reserves x1 (K2:
//   bottom 1) and reads top (K4). Store buffering: without a fence on both sides, K4 may read the old top 0
//   (the owner takes x1 without a CAS, believing two were left) while S3 reads the old bottom 2 (the thief's CAS
//   1 -> 2 succeeds and it steals x1 too): a duplicate. With both fences in the total order S, whichever fence
//   comes first makes the other side see its store. A lone last element needs no fence: then both sides go
//   through a CAS on top, and exactly one wins.
//   A failed CAS (K6, S5) loads with relaxed order (labelled_access.hpp): the loser returns without the element.
// ERRATUM (what we checked; details and sources in results/models_check/chaselev.md)
//   The one bug in the published C11 code that we found documented is fixed in the benchmark suite of
//   CDSChecker's authors (Norris & Demsky, OOPSLA'13; github.com/computersforpeace/model-checker-benchmarks,
//   chase-lev-deque-bugfix/deque.c, "Bug in paper...should have next line..."): after push resizes the buffer it
//   must reload the array pointer, or it writes the element into the old array. It concerns resize only, which
//   this deque does not have, and changes no memory order: the orders above are the paper's, unchanged. We found
//   no erratum text by the authors themselves. Two further pitfalls reported by implementers, both avoided here:
//   unsigned indices underflow when take reserves on an empty deque (crossbeam-rs/crossbeam PR #33) — ours are
//   signed; and a thief must read the element before its CAS, since afterwards the buffer may be freed by a
//   resize (crossbeam-rs/crossbeam PR #149) or, in a fixed ring, the slot reused by the owner — ours reads at S4,
//   before S5.
// PROGRESS
//   push and take are wait-free; steal is lock-free (it fails with kLostRace only when another operation
//   succeeded). Nothing here waits.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <type_traits>

#include "core/chase_lev_policies.hpp"
#include "core/labelled_access.hpp"
#include "core/site.hpp"
#include "core/std_backend.hpp"

namespace frontsteal {

enum class StealResult { kSuccess, kEmpty, kLostRace };

template <class T, class Backend = StdBackend, class Policy = ChaseLevOrders>
class ChaseLevDeque {
  static_assert(std::is_trivially_copyable_v<T>, "elements are copied through atomic slots");
  using A = Access<Backend, Policy>;
  template <class U>
  using Atomic = typename Backend::template Atomic<U>;
  // On the real machine a slot must not hide a lock (steal would then block on the owner).
  static_assert(!std::is_same_v<Atomic<T>, std::atomic<T>> || std::atomic<T>::is_always_lock_free);

 public:
  explicit ChaseLevDeque(std::size_t capacity_power_of_two = 64)
      : mask_(capacity_power_of_two - 1), buffer_(std::make_unique<Slot[]>(capacity_power_of_two)) {
    Backend::invariant(capacity_power_of_two >= 2 && (capacity_power_of_two & mask_) == 0,
                       "Chase-Lev capacity must be a power of two, at least 2");
  }

  // Owner only. False when full.
  bool push(T x) {
    const std::int64_t b = A::template load<Site::kPushReadBottom>(bottom_);  // B1
    const std::int64_t t = A::template load<Site::kPushReadTop>(top_);        // B2
    if (b - t > static_cast<std::int64_t>(mask_)) return false;
    A::template store<Site::kPushWriteSlot>(slot(b), x);          // B3
    A::template fence<Site::kPushReleaseFence>();                 // B4
    A::template store<Site::kPushPublishBottom>(bottom_, b + 1);  // B5
    return true;
  }

  // Owner only. False when empty (or when a thief won the last element).
  bool take(T& out) {
    const std::int64_t b = A::template load<Site::kTakeReadBottom>(bottom_) - 1;  // K1
    A::template store<Site::kTakeReserveBottom>(bottom_, b);                      // K2
    A::template fence<Site::kTakeFence>();                                        // K3
    std::int64_t t = A::template load<Site::kTakeReadTop>(top_);                  // K4
    if (t > b) {
      A::template store<Site::kTakeRestoreEmpty>(bottom_, b + 1);  // K7
      return false;
    }
    out = A::template load<Site::kTakeReadSlot>(slot(b));  // K5
    if (t < b) return true;
    // The last element (t == b): race the thieves for it. The planted defect keeps it as if others were left.
    if (has(Policy::defects(), Defect::kTakeLastWithoutCas)) return true;
    const bool won = A::template compare_exchange<Site::kTakeClaimLast>(top_, t, t + 1);  // K6
    A::template store<Site::kTakeRestoreLast>(bottom_, b + 1);                            // K8
    return won;
  }

  // Any thread.
  StealResult steal(T& out) {
    std::int64_t t = A::template load<Site::kStealReadTop>(top_);              // S1
    A::template fence<Site::kStealFence>();                                    // S2
    const std::int64_t b = A::template load<Site::kStealReadBottom>(bottom_);  // S3
    if (t >= b) return StealResult::kEmpty;
    const T x = A::template load<Site::kStealReadSlot>(slot(t));                                          // S4
    if (!A::template compare_exchange<Site::kStealClaim>(top_, t, t + 1)) return StealResult::kLostRace;  // S5
    out = x;
    return StealResult::kSuccess;
  }

  // Racy size, for statistics and tests.
  std::int64_t size_hint() const {
    return A::template load<Site::kHintReadBottom>(bottom_) - A::template load<Site::kHintReadTop>(top_);  // H1 H2
  }

 private:
  struct Slot {
    Atomic<T> value{T{}};
  };
  Atomic<T>& slot(std::int64_t i) const noexcept { return buffer_[static_cast<std::size_t>(i) & mask_].value; }

  alignas(64) Atomic<std::int64_t> top_{0};
  alignas(64) Atomic<std::int64_t> bottom_{0};
  std::size_t mask_;
  std::unique_ptr<Slot[]> buffer_;
};

}  // namespace frontsteal
