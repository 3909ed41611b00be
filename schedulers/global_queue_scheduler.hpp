// global_queue_scheduler.hpp — the paper's global queue (§4.1): one shared cursor over [0, N) under a
// std::mutex; a worker takes `grain` items per acquisition (default N / (100 P)) until the cursor passes N.
// Lock waits: an acquisition whose try_lock failed is counted, and the time until lock() returned is added
// to lock_wait_ns.
#pragma once

#include <algorithm>
#include <mutex>

#include "schedulers/scheduler.hpp"
#include "schedulers/team_scheduler.hpp"

namespace frontsteal::sched {

class GlobalQueueScheduler final : public TeamScheduler<GlobalQueueScheduler> {
 public:
  explicit GlobalQueueScheduler(const SchedulerConfig& config) : TeamScheduler(config.workers), claims_(config) {}

  ItemId grain() const noexcept { return claims_.grain; }

 private:
  friend class TeamScheduler<GlobalQueueScheduler>;
  void begin_frame() { next_ = 0; }  // published to the workers by the team's release (T1)
  void work(WorkerId w) {
    WorkerSlot& me = slot(w);
    for (;;) {
      if (!mutex_.try_lock()) {
        ++me.stats.lock_waits;
        const Clock::time_point start = Clock::now();
        mutex_.lock();
        me.stats.lock_wait_ns += nanoseconds_since(start);
      }
      const ItemId first = next_;
      const ItemId last = claims_.chunk_end(first);
      next_ = last;
      mutex_.unlock();
      if (first >= last) return;
      me.run_range(process(), first, last, w, claims_.timed);
    }
  }

  ChunkClaims claims_;
  std::mutex mutex_;
  ItemId next_ = 0;  // guarded by mutex_
};

}  // namespace frontsteal::sched
