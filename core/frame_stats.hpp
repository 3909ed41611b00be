// frame_stats.hpp — what one frame cost, per worker: the numbers behind utilization (paper Table 1) and the
// raw times of the loss account (where a worker's part of the frame went: wake-up, items, looking for work,
// stealing, waiting on ListTransient, the frame's end).
//
// The account's times partition a worker's part of the scheduler's own window [release, done] (wall_ns):
//   wake_ns + busy_ns + search_ns + steal_ns + termination_ns + (time between them no phase claims)
// where transient_wait_ns is part of search_ns or steal_ns, and busy_ns holds the `claims` timed claims, each
// of one or more items with the scheduler's per-item claim between them (the owner path of a drain). A scheduler fills
// what it can see: every scheduler wake_ns and termination_ns (from the clock reads it makes around its claims anyway);
// the stealing protocol (frame_loop.hpp) also search, steal and wait; the others leave those 0, so the time between
// their claims stays one term. The harness closes the account against its own clock
// (schedulers/main_job/loss_account.hpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace frontsteal {

struct WorkerFrameStats {
  std::uint64_t items_processed = 0;     // calls of the item function by this worker
  std::uint64_t claims = 0;              // timed claims: drains of its own list (stealing), chunks (others)
  std::uint64_t steal_attempts = 0;      // victims examined
  std::uint64_t steals_lock_busy = 0;    // ... whose LockList another thief held
  std::uint64_t steals_empty = 0;        // ... that had nothing left
  std::uint64_t steals_skipped_all = 0;  // ... whose whole share the victim claimed before the re-read
  std::uint64_t steals_succeeded = 0;    // ... that yielded a non-empty share
  std::uint64_t items_stolen = 0;        // items in the shares kept
  std::uint64_t items_skipped = 0;       // items dropped after the re-read of Front (the victim's claims)
  std::uint64_t lock_waits = 0;          // contended acquisitions of a shared lock (schedulers/ global queue)
  std::int64_t lock_wait_ns = 0;         // ... and the time spent waiting for it
  std::int64_t busy_ns = 0;              // time inside the owner loop (claiming and processing); other
                                         // schedulers: time processing the items of each claim
  std::int64_t idle_ns = 0;              // the rest of the worker's frame: stealing and waiting for the end
  std::int64_t active_ns = 0;            // wall time of the worker's part of the frame (wake-up to arrival);
                                         // oneTBB: the sum of its claims (its threads join the arena freely)
  std::int64_t cpu_ns = 0;               // thread CPU time over the same span (core/thread_cpu_time.hpp):
                                         // active − cpu is time off a CPU (descheduled, or asleep on a lock)
  std::int64_t wake_ns = 0;              // release of the frame → the start of this worker's first claim
  std::int64_t termination_ns = 0;       // the end of its last claim's items → the caller sees the frame done
  std::int64_t search_ns = 0;            // looking for work that was then found: victims examined, lock busy,
                                         // empty, polls (stealing only)
  std::int64_t steal_ns = 0;             // successful steals: victim's LockList held → share installed
  std::int64_t transient_wait_ns = 0;    // of search_ns + steal_ns, waiting at T4 on a victim's ListTransient

  WorkerFrameStats& operator+=(const WorkerFrameStats& o) {
    items_processed += o.items_processed;
    claims += o.claims;
    steal_attempts += o.steal_attempts;
    steals_lock_busy += o.steals_lock_busy;
    steals_empty += o.steals_empty;
    steals_skipped_all += o.steals_skipped_all;
    steals_succeeded += o.steals_succeeded;
    items_stolen += o.items_stolen;
    items_skipped += o.items_skipped;
    lock_waits += o.lock_waits;
    lock_wait_ns += o.lock_wait_ns;
    busy_ns += o.busy_ns;
    idle_ns += o.idle_ns;
    active_ns += o.active_ns;
    cpu_ns += o.cpu_ns;
    wake_ns += o.wake_ns;
    termination_ns += o.termination_ns;
    search_ns += o.search_ns;
    steal_ns += o.steal_ns;
    transient_wait_ns += o.transient_wait_ns;
    return *this;
  }
};

struct FrameStats {
  std::uint32_t frame = 0;
  std::int64_t wall_ns = 0;   // caller's view: release of the frame to its completion
  bool phases_timed = false;  // search_ns, steal_ns, transient_wait_ns measured (the stealing protocol with a
                              // SteadyPhaseTimer): the time between claims is split, not one term
  std::vector<WorkerFrameStats> workers;

  WorkerFrameStats totals() const {
    WorkerFrameStats t;
    for (const auto& w : workers) t += w;
    return t;
  }
  // Paper Table 1's utilization: busy time over the time all workers were available.
  double utilization() const {
    if (wall_ns <= 0 || workers.empty()) return 0.0;
    return static_cast<double>(totals().busy_ns) / (static_cast<double>(wall_ns) * workers.size());
  }
  // Max over mean busy time: 1.0 is perfect balance.
  double imbalance() const {
    if (workers.empty()) return 0.0;
    std::int64_t max_busy = 0;
    for (const auto& w : workers) max_busy = std::max(max_busy, w.busy_ns);
    const double mean = static_cast<double>(totals().busy_ns) / workers.size();
    return mean > 0 ? max_busy / mean : 0.0;
  }
};

}  // namespace frontsteal
