// chase_lev_scheduler.hpp — work stealing as Cilk and TBB do it, on Chase–Lev deques (chase_lev_deque.hpp):
// lazy binary splitting of ranges. Each worker starts a frame with its block [wN/P, (w+1)N/P) as one range;
// it takes a range from its deque, splits off upper halves onto its deque until at most `grain` items
// (default 1) are left, runs those, and takes again. An idle worker steals the oldest (largest) range from
// a random victim. The frame ends when the shared count of unprocessed items reaches 0.
//
// Steals: steal_attempts, steals_succeeded, steals_empty; a CAS lost to another thief counts in
// steals_lock_busy ("another thief got there first", as the stealing protocol's busy LockList).
// ORDERS: remaining_ fetch_sub release / load acquire — a worker that sees 0 sees every item's effects
// (not needed for correctness of the frame, which the team's T3 -> T4 orders, but it keeps the exit test
// honest under TSan).
#pragma once

#include <atomic>
#include <memory>
#include <random>

#include "core/std_backend.hpp"
#include "schedulers/chase_lev_deque.hpp"
#include "schedulers/scheduler.hpp"
#include "schedulers/team_scheduler.hpp"

namespace frontsteal::sched {

class ChaseLevScheduler final : public TeamScheduler<ChaseLevScheduler> {
 public:
  explicit ChaseLevScheduler(const SchedulerConfig& config)
      : TeamScheduler(config.workers),
        items_(config.items),
        grain_(config.grain ? config.grain : 1),
        timed_(config.time_claims),
        seed_(config.seed),
        deques_(config.workers) {}

 private:
  friend class TeamScheduler<ChaseLevScheduler>;
  void begin_frame() { remaining_.store(items_, std::memory_order::relaxed); }  // published by the team's release (T1)

  using Range = std::uint64_t;  // first << 32 | last
  static Range pack(ItemId first, ItemId last) { return std::uint64_t{first} << 32 | last; }
  static ItemId first_of(Range r) { return static_cast<ItemId>(r >> 32); }
  static ItemId last_of(Range r) { return static_cast<ItemId>(r); }

  struct alignas(64) PaddedDeque {
    ChaseLevDeque<Range> deque{128};  // a split chain of 2^32 items is 33 deep
  };

  // Runs `r` and everything split off it onto this worker's deque, until the deque is empty: one timed run of
  // claims (WorkerSlot::begin_run), as the stealing owner's drain is; with leaves of one item, a clock read pair
  // per leaf would cost more than the take.
  void process_range(WorkerId w, Range r) {
    WorkerSlot& me = slot(w);
    ChaseLevDeque<Range>& mine = deques_[w].deque;
    ItemId first = first_of(r), last = last_of(r);
    me.begin_run(timed_);
    ItemId ran = 0;
    for (;;) {
      while (last - first > grain_) {
        const ItemId mid = first + (last - first) / 2;
        mine.push(pack(mid, last));  // cannot fail: occupancy ≤ split depth ≤ 33 < 128
        last = mid;
      }
      for (ItemId id = first; id < last; ++id) me.run(process(), id, w);
      ran += last - first;
      Range next;
      if (!mine.take(next)) break;
      first = first_of(next);
      last = last_of(next);
    }
    // One subtraction per run, not per leaf: a locked RMW after each item would wait for the item's stores to
    // drain (~30 ns here); the count only has to reach 0 once every run has ended.
    remaining_.fetch_sub(ran, std::memory_order::release);
    me.end_run(timed_);
  }

  void work(WorkerId w) {
    const WorkerId p = worker_count();
    const ItemId first = static_cast<ItemId>(std::uint64_t{items_} * w / p);
    const ItemId last = static_cast<ItemId>(std::uint64_t{items_} * (w + 1) / p);
    if (first < last) process_range(w, pack(first, last));
    WorkerSlot& me = slot(w);
    std::minstd_rand rng(static_cast<std::uint32_t>(seed_ * 7919 + w * 104729 + me.stats.items_processed));
    for (std::uint32_t spins = 0; remaining_.load(std::memory_order::acquire) != 0; ++spins) {
      // The same back-off as the stealing protocol's idle loop: pause, then yield the core (oversubscription).
      StdBackend::spin_pause(Site::kActivePoll, spins);
      if (p == 1) continue;
      WorkerId victim = static_cast<WorkerId>(rng() % (p - 1));
      if (victim >= w) ++victim;
      Range r;
      ++me.stats.steal_attempts;
      switch (deques_[victim].deque.steal(r)) {
        case StealResult::kSuccess:
          ++me.stats.steals_succeeded;
          me.stats.items_stolen += last_of(r) - first_of(r);
          process_range(w, r);
          spins = 0;
          break;
        case StealResult::kEmpty: ++me.stats.steals_empty; break;
        case StealResult::kLostRace: ++me.stats.steals_lock_busy; break;
      }
    }
  }

  ItemId items_;
  ItemId grain_;
  bool timed_;
  std::uint64_t seed_;
  alignas(64) std::atomic<std::uint64_t> remaining_{0};
  std::vector<PaddedDeque> deques_;
};

}  // namespace frontsteal::sched
