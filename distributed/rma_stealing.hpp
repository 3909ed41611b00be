// rma_stealing.hpp — the load-stealing protocol of core/stealing_protocol.hpp with every rank's slot in an
// MPI-3 window (rma_window.hpp): the owner claims with local loads and stores on its own window memory, a
// thief on another rank steals with MPI_Get / MPI_Put / MPI_Compare_and_swap, each flushed.
//
// SAME PROTOCOL, SAME LABELS. Every shared access below carries the label of core/site.hpp (O1, F1, O2, O3, O4,
// T1-T5, L1-L3, I1-I2, A1-A3, E4) in a comment on its line, in the order of stealing_protocol.hpp, so the two
// files can be compared line by line. What each site becomes:
//   O1  local atomic_ref store ListTransient := 1        O2  local atomic_ref load of End (acquire)
//   F1  seq_cst fence (+ MPI_Win_sync: --owner-fence, G3)  O3  local store Front := f + 1 (release)
//   O4  local store ListTransient := 0 (release)           T1, T2, T5  MPI_Get + MPI_Win_flush
//   T3  MPI_Put End := mid + MPI_Win_flush                 F2  that flush: the Put is complete at the target (G5)
//   T4  MPI_Get ListTransient + flush, repeated until 0    L1  MPI_Fetch_and_op(MPI_NO_OP); L2 MPI_Compare_and_swap;
//   L3  MPI_Accumulate(MPI_REPLACE)                        A1, A2  MPI_Fetch_and_op(MPI_SUM) on rank 0; A3 NO_OP
// (G1-G5: rma_window.hpp's list of the MPI guarantees this rests on, and what it assumes beyond them.)
//
// WHY THE CORE SOURCE IS NOT REUSED THROUGH THE BACKEND SEAM. core's Owner/Thief are generic over a Backend,
// but the seam is an *object* seam: every operation takes a reference to a Backend::Atomic<T> that lives in
// the caller's address space, and the protocol's state types own their cells (ActivitySlot constructs its
// atomics with in-class initializers and allocates its list body with make_unique; TryLock owns `held_`;
// ActiveWorkers owns `count_`; the frame boundary blocks on Atomic::wait). A thief's view of another rank's
// slot is an address (rank, displacement) in a window, not an object, and every remote read must be followed
// by a flush before its value exists. An RMA backend would need Atomic<T> to be a (window, rank, displacement)
// handle that ActivitySlot could be constructed *around*, one slot object per remote rank per thief, and
// ActiveWorkers pointed at rank 0's word — a change to core's state types, not a new backend. Rather than
// change core's types under every other checker (Relacy, TSan, stress), this file restates the protocol with
// the same labels, the same steps in the same order and the same invariants (I1-I6 of stealing_protocol.hpp,
// I-T of active_workers.hpp); it reuses core's pure pieces (IdRange, RangeList, append_merging,
// items_left_to_victim). The planted defects are the core's (Defect::kSkipFrontReread).
//
// PROGRESS. Owner: wait-free; no MPI call per claim by default (F1 a CPU fence), one with F1 = MPI_Win_sync.
// Thief: blocks at T4 while the victim is between O1 and O4, as in core. One more dependency than in shared
// memory: with an RMA transport that needs the target's help (Open MPI over TCP: osc/pt2pt, osc/rdma on
// btl/tcp) every thief operation completes only when the victim calls into MPI; the frame runner's busy owner
// then makes a progress call between items (owner_progress.hpp, --owner-progress), which is outside O1..O4.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <thread>
#include <vector>

#include "core/id_range.hpp"
#include "core/policies.hpp"
#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

// The termination count (active_workers.hpp, I-T) in rank 0's part of the window. Rank 0 does nothing for it:
// it is a memory word with a home, not a master (passive target).
class RmaActiveCount {
 public:
  explicit RmaActiveCount(RmaWindow& w) : w_(w) {}
  void join() { w_.fetch_and_op(0, kActive, 1, MPI_SUM); }     // A1
  void leave() { w_.fetch_and_op(0, kActive, -1, MPI_SUM); }   // A2
  bool all_idle() { return w_.atomic_read(0, kActive) == 0; }  // A3
  std::int32_t value() { return w_.atomic_read(0, kActive); }
  void rearm(std::int32_t ranks) { w_.accumulate_replace(0, kActive, ranks); }  // E4 (rank 0, between frames)

 private:
  RmaWindow& w_;
};

// Owner: claims from the front of this rank's own list, in its own window memory.
class RmaOwner {
 public:
  // win_sync_f1: F1 is MPI_Win_sync (G3, the standard's memory barrier) followed by a seq_cst fence; without
  // it F1 is the seq_cst fence alone, which is all osc/sm's MPI_Win_sync does besides calling the progress
  // engine — and with mpi_yield_when_idle that progress call yields the CPU on every claim (measured:
  // milliseconds per claim beside busy processes). See docs/mpi.md.
  RmaOwner(RmaWindow& w, int me, bool win_sync_f1 = true) : w_(w), me_(me), win_sync_f1_(win_sync_f1) {}

  std::optional<ItemId> try_claim() {
    w_.local(kTransient).store(1u, std::memory_order_relaxed);                 // O1
    if (win_sync_f1_) w_.sync();                                               // F1 (G3)
    std::atomic_thread_fence(std::memory_order_seq_cst);                       // F1 (CPU order)
    const std::uint32_t end = w_.local(kEnd).load(std::memory_order_acquire);  // O2
    const std::uint32_t f = front_;
    if (f >= end) {
      w_.local(kTransient).store(0u, std::memory_order_release);  // O4
      return std::nullopt;
    }
    w_.local(kFront).store(f + 1, std::memory_order_release);   // O3
    w_.local(kTransient).store(0u, std::memory_order_release);  // O4
    front_ = f + 1;
    const WinEntry* entries = w_.local_entries();
    while (f >= entry_.flat_end()) entry_ = entries[++entry_index_];
    return entry_.begin + (f - entry_.flat_begin);
  }

  // Installs `list` into this rank's slot under its own LockList (taken with MPI_Compare_and_swap on itself:
  // the lock word is accumulate-only, G4). Only when the current list is exhausted, or between frames.
  void install(const RangeList& list, std::uint32_t spin_pause_us = 0) {
    for (std::uint32_t spins = 0; w_.compare_and_swap(me_, kLock, 0u, 1u) != 0u; ++spins) {  // L2 (owner, idle)
      if (spins > 64) std::this_thread::sleep_for(std::chrono::microseconds(spin_pause_us + 1));
    }
    WinEntry* entries = w_.local_entries();
    std::uint32_t flat = 0;
    std::uint32_t n = 0;
    for (const IdRange& r : list) {
      if (r.empty()) continue;
      entries[n++] = WinEntry{r.begin, r.end, flat};
      flat += r.size();
    }
    w_.local(kEntryCount).store(n, std::memory_order_relaxed);
    w_.local(kFront).store(0u, std::memory_order_relaxed);  // I1
    w_.local(kEnd).store(flat, std::memory_order_release);  // I2
    w_.sync();                                              // publish (G3)
    w_.accumulate_replace(me_, kLock, 0u);                  // L3
    front_ = 0;
    entry_index_ = 0;
    entry_ = n > 0 ? entries[0] : WinEntry{};
  }

  std::uint32_t claimed() const noexcept { return front_; }

 private:
  RmaWindow& w_;
  int me_;
  bool win_sync_f1_;
  std::uint32_t front_ = 0;
  std::uint32_t entry_index_ = 0;
  WinEntry entry_{};
};

enum class RmaStealOutcome : std::uint8_t { kLockBusy, kEmpty, kSkippedAll, kStolen };

// Test hooks (never set in measured runs): a forced interleaving for the negative control and its twin.
struct RmaStealHooks {
  // After T1/T2 and before T3, wait (MPI_Get of Front, bounded by overlap_timeout) until the victim has
  // claimed at least one item of the planned share, so the re-read (T4/T5) has something to catch. Forces the
  // interleaving the skip-reread defect gets wrong, deterministically.
  bool force_overlap = false;
  std::chrono::milliseconds overlap_timeout{5000};
  Defect defects = Defect::kNone;  // only Defect::kSkipFrontReread is honoured here
};

// Thief: takes the second half of a victim's unclaimed items into a private staging list.
class RmaThief {
 public:
  RmaThief(RmaWindow& w, RmaActiveCount& active) : w_(w), active_(active), staging_(w.capacity()) {}

  RmaStealOutcome try_steal(int victim, const RmaStealHooks& hooks = {}) {
    if (w_.atomic_read(victim, kLock) != 0u) return RmaStealOutcome::kLockBusy;               // L1
    if (w_.compare_and_swap(victim, kLock, 0u, 1u) != 0u) return RmaStealOutcome::kLockBusy;  // L2
    const std::uint32_t front = w_.get(victim, kFront);                                       // T1
    const std::uint32_t end = w_.get(victim, kEnd);                                           // T2
    if (front >= end) {
      w_.accumulate_replace(victim, kLock, 0u);  // L3
      return RmaStealOutcome::kEmpty;
    }
    mid_ = front + static_cast<std::uint32_t>(items_left_to_victim(end - front));
    end_ = end;
    copy_share(victim);
    if (hooks.force_overlap) await_victim_past_mid(victim, hooks.overlap_timeout);
    active_.join();              // A1 (before T3: I-T)
    w_.put(victim, kEnd, mid_);  // T3 + F2 (flush, G5)
    std::uint32_t front_after = mid_;
    if (!has(hooks.defects, Defect::kSkipFrontReread)) {
      const auto wait_start = std::chrono::steady_clock::now();
      for (std::uint32_t spins = 0; w_.get(victim, kTransient) != 0u; ++spins) {  // T4
        if (spins > 64) std::this_thread::yield();
        ++t4_spins_;
      }
      t4_wait_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - wait_start).count();
      front_after = w_.get(victim, kFront);  // T5
    }
    w_.accumulate_replace(victim, kLock, 0u);  // L3
    return keep_unclaimed(front_after);
  }

  const RangeList& share() const noexcept { return share_; }
  std::uint32_t skipped() const noexcept { return skipped_; }
  // Diagnostics: time spent, and polls made, waiting at T4 for a victim's claim in flight.
  double t4_wait_s() const noexcept { return t4_wait_s_; }
  std::uint64_t t4_spins() const noexcept { return t4_spins_; }

 private:
  // Copies the victim's entries that overlap [mid, end) (before T3, as core's plan_share).
  void copy_share(int victim) {
    share_.clear();
    const std::uint32_t n = w_.get(victim, kEntryCount);
    // Binary search over remote entries would cost log n round trips; one Get of the whole body costs one
    // (entries are 12 bytes; lists are short because they are merged ranges).
    w_.get_entries(victim, 0, n, staging_.data());
    for (std::uint32_t i = 0; i < n; ++i) {
      const WinEntry& e = staging_[i];
      if (e.flat_end() <= mid_) continue;
      if (e.flat_begin >= end_) break;
      const std::uint32_t lo = std::max(mid_, e.flat_begin);
      const std::uint32_t hi = std::min(end_, e.flat_end());
      append_merging(share_, {e.begin + (lo - e.flat_begin), e.begin + (hi - e.flat_begin)});
    }
  }

  void await_victim_past_mid(int victim, std::chrono::milliseconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (w_.get(victim, kFront) <= mid_ && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  }

  RmaStealOutcome keep_unclaimed(std::uint32_t front_after) {
    skipped_ = front_after > mid_ ? std::min(front_after, end_) - mid_ : 0;
    std::uint32_t drop = skipped_;
    std::size_t whole = 0;
    while (whole < share_.size() && share_[whole].size() <= drop) drop -= share_[whole++].size();
    share_.erase(share_.begin(), share_.begin() + static_cast<std::ptrdiff_t>(whole));
    if (!share_.empty()) share_.front().begin += drop;
    if (share_.empty()) {
      active_.leave();  // A2: empty share
      return RmaStealOutcome::kSkippedAll;
    }
    return RmaStealOutcome::kStolen;
  }

  RmaWindow& w_;
  RmaActiveCount& active_;
  std::vector<WinEntry> staging_;
  RangeList share_;
  std::uint32_t mid_ = 0;
  std::uint32_t end_ = 0;
  std::uint32_t skipped_ = 0;
  double t4_wait_s_ = 0;
  std::uint64_t t4_spins_ = 0;
};

}  // namespace frontsteal::mpi
