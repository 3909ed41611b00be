// stealing_protocol.hpp — wait-free-owner load stealing over ranges of item ids.
//
// Based on: Kumar, Chang & Manocha, "Scalable Algorithms for Interactive Visualization of Curved Surfaces",
// SC'96, §4.2 (tessellation loop, LockList, "delete the second half", re-read Front, ListTransient).
// Memory-model reading: the ListTransient handshake is a store->load (Dekker) pattern; without a StoreLoad
// fence on the owner it is at-least-once ("idempotent work stealing", Michael, Vechev & Saraswat, PPoPP'09;
// "Laws of Order", Attiya et al., POPL'11: exactly-once stealing needs a StoreLoad fence or an RMW on the
// owner's take). Asymmetric fences: Dice, Huang & Yang, "Asymmetric Dekker Synchronization" (2001 tech report);
// Linux membarrier(2).
//
// ROLES (types)
//   Owner<B,P>   one per worker, used only by that worker's thread; not copyable. Claims items from the front
//                of its own list and installs new lists into its own slot.
//   Thief<B,P>   one per worker, used by the same thread while its own list is empty. Steals the second half
//                of another worker's unclaimed items into a private staging list.
//
// OWNERSHIP of ActivitySlot (see activity_list.hpp for the layout)
//   field        writer                                       readers
//   front        owner: O3 per claim, I1 at install (*)       thieves under LockList: T1, T5
//   transient    owner: O1, O4                                thieves under LockList: T4
//   end          thieves under LockList: T3;                  owner: O2 (no lock); thieves under LockList: T2
//                owner under its own LockList: I2
//   entries      owner under its own LockList, at install (*) owner; thieves under LockList
//   (*) between frames, the thread that prepares the next frame installs every list while all workers wait
//       (frame_loop.hpp, F1); its writes reach the owner through the frame boundary's release/acquire.
//
// INVARIANTS
//   I1  Thieves of one victim are serialized by its LockList; the owner of a list takes that lock only when
//       its list is exhausted (to install a new one), never to claim.
//   I2  End only decreases between two installs, and only under LockList.
//   I3  The owner claims flat position f (O3: Front := f+1) only after reading End > f at O2 of the same
//       claim, with ListTransient raised from before O2 until after O3. A batched claim (try_claim_up_to) takes
//       positions [f, f+k) in one handshake, O3 storing Front := f+k, only after reading End >= f+k at O2.
//   I4  Exactly-once (policies with forbids_store_buffering): after a steal's T5 reads Front = g, the owner
//       never claims a position >= max(g, mid) of the stolen tail [mid, e); the thief keeps [max(mid, g), e)
//       and the owner keeps everything it claimed. Each position is processed by exactly one worker.
//   I5  At-least-once (every policy): every position of [0, e) is kept by the owner or by the thief; a
//       position may be kept by both (store buffering at the handshake), never by neither.
//   I6  The owner path (try_claim) executes no lock, no read-modify-write and no wait: it is wait-free, a
//       bounded number of its own steps whatever other threads do.
//
// LINEARIZATION POINTS
//   claim       O3 (the store of Front) for a successful claim, single or batched; O2 for "list exhausted".
//   steal       T3 (the store of End := mid); the share's lower bound is fixed later, at T5.
//   install     I2 (the store of End), under the owner's own LockList.
//
// LABELLED ORDERS AND FENCES (orders per policy in policies.hpp; "-" = no ordering needed for that pairing)
//   O1 ListTransient := 1      -- with F1, is seen by T4 unless O2 sees T3 (store buffering, F1 <-> F2)
//   F1 owner StoreLoad fence   -- pairs with F2 (seq_cst fences) or with the heavy membarrier (Asymmetric)
//   O2 read End                -- see F1; reads T3 or a later install
//   O3 Front := f + 1          -- made visible to T5 through O4 -> T4 (f + k for a batch of k)
//   O4 ListTransient := 0      -- release: pairs with T4's acquire, so T5 sees O3
//   T1 read Front              -- sizes the share; a stale value is corrected at T5
//   T2 read End                -- protected by LockList (L2 acquire <-> L3 release, I2 under the lock)
//   T3 End := mid              -- with F2, seen by O2 unless T4 sees O1
//   F2 thief StoreLoad fence   -- pairs with F1
//   T4 await ListTransient==0  -- acquire: pairs with O4
//   T5 re-read Front           -- after T4, sees every claim whose O2 missed T3
//   L1-L3 (try_lock.hpp), I1-I2 (install), A1-A3 (active_workers.hpp), E1-E6 (frame_loop.hpp)
//
// KNOWN BENIGN RACES
//   A thief reads Front (T1) while the owner advances it: the share is sized on an old value; T5 corrects.
//   The owner reads End (O2) while a thief lowers it: it may claim one item of the tail; T4/T5 see that claim
//   (exactly-once policies) or the item runs twice (Paper).
//
// PROGRESS
//   Owner: wait-free (I6). Thief: blocking at T4. A thief waits for ListTransient to fall, so it starves
//   while the victim is preempted between O1 and O4 (paper §4.2.2: "p_i is prone to starvation"). Other
//   thieves of the same victim wait behind it only in the sense that their try_lock fails and they move on.
//   A ListTransient that is never lowered would keep a thief at T4 forever, holding the victim's LockList:
//   every real-thread test and stress run is watched for exactly that kind of hang (stress/watchdog.hpp; its
//   negative control is Broken:NeverRetracts).
//
// CHECKED BY
//   tests/core/stealing_protocol_test.cpp (deterministic step-by-step interleavings, real threads),
//   models_check/ (Relacy, every policy and mutant), stress/ (ThreadSanitizer, chaos; release x86 rates).
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>

#include "core/active_workers.hpp"
#include "core/activity_list.hpp"
#include "core/check.hpp"
#include "core/id_range.hpp"
#include "core/labelled_access.hpp"
#include "core/policies.hpp"

namespace frontsteal {

// ---------------------------------------------------------------------------------------------------------
// Owner: claims from the front of its own list.
// ---------------------------------------------------------------------------------------------------------
template <class Backend, class Policy>
class Owner {
 public:
  using Slot = ActivitySlot<Backend, Policy>;

  explicit Owner(Slot& slot) noexcept : slot_(slot) {}
  Owner(const Owner&) = delete;
  Owner& operator=(const Owner&) = delete;

  // One claim (paper §4.2.1 lines 1-2): the id of the claimed item, or nullopt when the list is exhausted.
  // Wait-free: five shared accesses, no lock, no read-modify-write.
  [[nodiscard]] std::optional<ItemId> try_claim() noexcept {
    announce();
    storeload_fence();
    return finish_claim(read_end());
  }

  // The steps of try_claim, public so tests can interleave them with a thief's steps one at a time.
  void announce() noexcept {
    if (!has(Policy::defects(), Defect::kOwnerSkipsTransient)) {
      A::template store<Site::kOwnerAnnounce>(slot_.transient, std::uint32_t{1});  // O1
    }
  }
  void storeload_fence() noexcept { A::template fence<Site::kOwnerStoreLoadFence>(); }  // F1
  [[nodiscard]] std::uint32_t read_end() noexcept {
    return A::template load<Site::kOwnerReadEnd>(slot_.end);  // O2
  }
  [[nodiscard]] std::optional<ItemId> finish_claim(std::uint32_t end) noexcept {
    const std::uint32_t f = front_;
    if (f >= end) {
      retract();
      return std::nullopt;
    }
    A::template store<Site::kOwnerClaimFront>(slot_.front, f + 1);  // O3: the claim's linearization point
    retract();
    front_ = f + 1;
    // Walk the private cursor to the range holding f (plain reads of our own list, outside the handshake).
    while (f >= entry_.flat_end()) entry_ = A::read(slot_.entries[++entry_index_]);
    return entry_.ids.begin + (f - entry_.flat_begin);
  }

  // A batched claim: up to n consecutive positions of the entry that holds Front, in one handshake (O1 F1 O2 O3
  // O4, with O3 storing Front := f + k). The ids claimed, or nullopt when the list is exhausted (or n is 0).
  // k is bounded by n, by the entry (so the ids are one range) and by the End read at O2 (I3 for every claimed
  // position). Wait-free, as try_claim: the same five shared accesses, plus plain reads of the owner's own list.
  [[nodiscard]] std::optional<IdRange> try_claim_up_to(std::uint32_t n) noexcept {
    announce();
    storeload_fence();
    return finish_claim_up_to(read_end(), n);
  }
  // The second half of try_claim_up_to, after O1, F1 and O2 (tests interleave it with a thief's steps).
  [[nodiscard]] std::optional<IdRange> finish_claim_up_to(std::uint32_t end, std::uint32_t n) noexcept {
    seek_front_entry();  // plain reads of our own list: no shared step between O2 and O3
    const std::uint32_t f = front_;
    if (f >= end || n == 0) {
      retract();
      return std::nullopt;
    }
    // kBatchIgnoresEnd (negative control only) bounds the batch by the entry alone.
    const std::uint32_t bound = has(Policy::defects(), Defect::kBatchIgnoresEnd) ? entry_.flat_end() : end;
    const std::uint32_t last = std::min({bound, entry_.flat_end(), f + n});
    A::template store<Site::kOwnerClaimFront>(slot_.front, last);  // O3: the batch's linearization point
    retract();
    front_ = last;
    return IdRange{entry_.ids.begin + (f - entry_.flat_begin), entry_.ids.begin + (last - entry_.flat_begin)};
  }
  // The ids the next batched claim would take if no thief intervened: the rest of the entry that holds Front
  // (empty when the list is exhausted as far as the owner's own copy of it knows). Plain reads of the owner's
  // own list; callers size a batch with it (by cost, not by count) and the claim itself is bounded by End.
  [[nodiscard]] IdRange unclaimed_run() noexcept {
    seek_front_entry();
    if (front_ < entry_.flat_begin || front_ >= entry_.flat_end()) return {};
    return {entry_.ids.begin + (front_ - entry_.flat_begin), entry_.ids.end};
  }

  // Replaces the (exhausted) list with `list`, under the slot's LockList so no thief reads a half-written body.
  // Called by the owner's thread after a successful steal, and between frames by whichever thread prepares
  // the next frame while every worker waits; never while items of the old list are unclaimed.
  void install(std::span<const IdRange> list) noexcept {
    slot_.lock.lock_spinning();
    std::uint32_t flat = 0;
    std::uint32_t n = 0;
    for (const IdRange& r : list) {
      if (r.empty()) continue;
      Backend::invariant(n < slot_.capacity, "install: list has more ranges than the slot holds");
      A::write(slot_.entries[n++], SegmentEntry{r, flat});
      flat += r.size();
    }
    A::write(slot_.entry_count, n);
    A::template store<Site::kInstallFront>(slot_.front, std::uint32_t{0});  // I1
    A::template store<Site::kInstallEnd>(slot_.end, flat);                  // I2: install's linearization point
    slot_.lock.unlock();
    front_ = 0;
    entry_index_ = 0;
    entry_ = n > 0 ? A::read(slot_.entries[0]) : SegmentEntry{};
  }

  // Appends the ids claimed from the current list to `log` (what this worker processed: its share of the
  // next frame's allocation, paper §4.2.1 temporal coherence).
  void log_claimed(RangeList& log) const noexcept {
    const std::uint32_t n = A::read(slot_.entry_count);
    for (std::uint32_t i = 0; i < n; ++i) {
      const SegmentEntry e = A::read(slot_.entries[i]);
      if (e.flat_begin >= front_) break;
      const std::uint32_t taken = std::min(e.ids.size(), front_ - e.flat_begin);
      append_merging(log, {e.ids.begin, e.ids.begin + taken});
    }
  }

  // Positions claimed from the current list (the owner's private copy of Front).
  std::uint32_t claimed() const noexcept { return front_; }

 private:
  using A = Access<Backend, Policy>;

  // Moves the private cursor to the entry holding flat position front_ (plain reads of our own list; it stays
  // on the last entry once the list is used up).
  void seek_front_entry() noexcept {
    const std::uint32_t n = A::read(slot_.entry_count);
    while (front_ >= entry_.flat_end() && entry_index_ + 1 < n) entry_ = A::read(slot_.entries[++entry_index_]);
  }

  void retract() noexcept {
    // kOwnerNeverRetracts (negative control only) leaves ListTransient raised: a thief hangs at T4.
    if (!has(Policy::defects(), Defect::kOwnerSkipsTransient | Defect::kOwnerNeverRetracts)) {
      A::template store<Site::kOwnerRetract>(slot_.transient, std::uint32_t{0});  // O4
    }
  }

  Slot& slot_;
  std::uint32_t front_ = 0;        // private copy of Front[p]: only this thread writes Front
  std::uint32_t entry_index_ = 0;  // cursor: the entry that holds flat position front_ - 1 (or 0)
  SegmentEntry entry_{};           // cached copy of entries[entry_index_]
};

// ---------------------------------------------------------------------------------------------------------
// Thief: takes the second half of a victim's unclaimed items.
// ---------------------------------------------------------------------------------------------------------
enum class [[nodiscard]] StealOutcome : std::uint8_t{
    kLockBusy,    // another thief holds the victim's LockList: move on (paper line 63)
    kEmpty,       // the victim had no unclaimed item
    kSkippedAll,  // the victim claimed the whole share before the re-read: nothing kept
    kStolen,      // share() holds at least one item, ready to install
};

// What try_steal tells an observer: the victim's LockList is held (locked); the share is planned, End not yet
// lowered (planned: optional, for tests that hold a thief there to force an interleaving); a wait at T4 begins
// (wait_begins, at the first poll that finds ListTransient raised) and is over (wait_over, after every attempt
// that reached T4, whether it waited or not). The default does nothing and compiles away.
struct NoStealObserver {
  void locked() noexcept {}
  void planned() noexcept {}
  void wait_begins() noexcept {}
  void wait_over() noexcept {}
};

template <class Backend, class Policy>
class Thief {
 public:
  using Slot = ActivitySlot<Backend, Policy>;

  Thief(ActiveWorkers<Backend, Policy>& active, std::uint32_t max_entries) : active_(active) {
    share_.reserve(max_entries);  // so the steal path never allocates
  }
  Thief(const Thief&) = delete;
  Thief& operator=(const Thief&) = delete;

  // One steal attempt (paper §4.2.1 lines 62-66 with §4.2.2 lines 651-654). `observe` is told when the
  // victim's LockList is held and when a wait at T4 starts and ends (the loss account's clock reads, see
  // NoStealObserver); it reads no shared state and changes no step.
  template <class Observer = NoStealObserver>
  StealOutcome try_steal(Slot& victim, Observer&& observe = Observer{}) noexcept {
    if (!lock_victim(victim)) return StealOutcome::kLockBusy;
    observe.locked();
    if (!plan_share(victim)) {
      unlock_victim(victim);
      return StealOutcome::kEmpty;
    }
    if constexpr (requires { observe.planned(); }) observe.planned();
    shrink_victim(victim);
    storeload_fence();
    for (std::uint32_t spins = 0; !victim_quiescent(victim); ++spins) {
      if (spins == 0) observe.wait_begins();
      Backend::spin_pause(Site::kThiefAwaitTransient, spins);
    }
    observe.wait_over();
    const std::uint32_t front_after = reread_front(victim);
    unlock_victim(victim);
    return keep_unclaimed(front_after);
  }

  // The steps of try_steal, public so tests can interleave them with the owner's steps one at a time.
  [[nodiscard]] bool lock_victim(Slot& victim) noexcept { return victim.lock.try_lock(); }
  void unlock_victim(Slot& victim) noexcept { victim.lock.unlock(); }

  // Reads the victim's unclaimed range and copies the second half into the private staging list.
  // Returns false when there is nothing to take.
  [[nodiscard]] bool plan_share(Slot& victim) noexcept {
    const std::uint32_t front = A::template load<Site::kThiefReadFront>(victim.front);  // T1
    const std::uint32_t end = A::template load<Site::kThiefReadEnd>(victim.end);        // T2
    if (front >= end) return false;
    mid_ = front + static_cast<std::uint32_t>(items_left_to_victim(end - front));
    end_ = end;
    // Copy before shrinking (T3): once End is lowered the victim may exhaust its list and install a new body.
    share_.clear();
    const std::uint32_t n = A::read(victim.entry_count);
    for (std::uint32_t i = first_entry_at(victim, n, mid_); i < n; ++i) {
      const SegmentEntry e = A::read(victim.entries[i]);
      if (e.flat_begin >= end_) break;
      // An entry that starts above mid is copied from its own start (max): the share spans several entries.
      const std::uint32_t lo = has(Policy::defects(), Defect::kShareLowerBound) ? mid_  // negative control only
                                                                                : std::max(mid_, e.flat_begin);
      const std::uint32_t hi = std::min(end_, e.flat_end());
      append_merging(share_, {e.ids.begin + (lo - e.flat_begin), e.ids.begin + (hi - e.flat_begin)});
    }
    return true;
  }

  // Joins the active workers (termination, A1) and lowers the victim's End: the steal's linearization point.
  // A1 must come first (I-T of active_workers.hpp): once End is lowered the victim may exhaust its list and
  // leave, and the share [mid, e) is then held by no counted worker until A1.
  void shrink_victim(Slot& victim) noexcept {
    if (has(Policy::defects(), Defect::kThiefJoinsLate)) {         // negative control only: the order reversed
      A::template store<Site::kThiefShrinkEnd>(victim.end, mid_);  // T3
      active_.join();                                              // A1 (too late)
      return;
    }
    active_.join();                                              // A1
    A::template store<Site::kThiefShrinkEnd>(victim.end, mid_);  // T3
  }
  void storeload_fence() noexcept { A::template fence<Site::kThiefStoreLoadFence>(); }  // F2

  // One poll of the victim's ListTransient: true when no claim is in flight.
  [[nodiscard]] bool victim_quiescent(Slot& victim) noexcept {
    if (has(Policy::defects(), Defect::kSkipFrontReread)) return true;
    return A::template load<Site::kThiefAwaitTransient>(victim.transient) == 0u;  // T4
  }
  [[nodiscard]] std::uint32_t reread_front(Slot& victim) noexcept {
    if (has(Policy::defects(), Defect::kSkipFrontReread)) return mid_;
    return A::template load<Site::kThiefRereadFront>(victim.front);  // T5
  }

  // Drops the items the victim claimed before T5 (paper line 654: "start after new Front").
  StealOutcome keep_unclaimed(std::uint32_t front_after) noexcept {
    skipped_ = front_after > mid_ ? std::min(front_after, end_) - mid_ : 0;
    std::uint32_t drop = skipped_;
    std::size_t whole = 0;
    while (whole < share_.size() && share_[whole].size() <= drop) drop -= share_[whole++].size();
    share_.erase(share_.begin(), share_.begin() + static_cast<std::ptrdiff_t>(whole));
    if (!share_.empty()) share_.front().begin += drop;
    if (share_.empty()) {
      active_.leave();  // A2: the share came out empty; we hold no work
      return StealOutcome::kSkippedAll;
    }
    return StealOutcome::kStolen;
  }

  // The staged share after keep_unclaimed returned kStolen.
  std::span<const IdRange> share() const noexcept { return share_; }
  // Items dropped by the last keep_unclaimed because the victim had already claimed them.
  std::uint32_t skipped() const noexcept { return skipped_; }
  // The last planned split point and end (flat positions of the victim's list).
  std::uint32_t planned_mid() const noexcept { return mid_; }
  std::uint32_t planned_end() const noexcept { return end_; }

 private:
  using A = Access<Backend, Policy>;

  // Binary search for the entry holding flat position `pos` (entries are sorted by flat_begin).
  static std::uint32_t first_entry_at(Slot& victim, std::uint32_t n, std::uint32_t pos) noexcept {
    std::uint32_t lo = 0;
    std::uint32_t hi = n;
    while (hi - lo > 1) {
      const std::uint32_t m = lo + (hi - lo) / 2;
      if (A::read(victim.entries[m]).flat_begin <= pos)
        lo = m;
      else
        hi = m;
    }
    return lo;
  }

  ActiveWorkers<Backend, Policy>& active_;
  RangeList share_;  // staging: private to this thread
  std::uint32_t mid_ = 0;
  std::uint32_t end_ = 0;
  std::uint32_t skipped_ = 0;
};

}  // namespace frontsteal
