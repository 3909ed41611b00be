// global_queue_scheduler.hpp — the paper's global queue (§4.1): one shared cursor over [0, N) under a
// std::mutex; a worker takes `grain` items per acquisition (default N / (100 P)) until the cursor passes N.
// Lock waits: an acquisition whose try_lock failed is counted, and the time until lock() returned is added
// to lock_wait_ns.
#pragma once

#include <algorithm>
#include <mutex>

#include "schedulers/scheduler.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {

class GlobalQueueScheduler final : public Scheduler {
 public:
  explicit GlobalQueueScheduler(const SchedulerConfig& config)
      : items_(config.items),
        grain_(config.grain ? config.grain : default_grain(config.items, config.workers)),
        timed_(config.time_claims),
        slots_(config.workers),
        team_(config.workers, [this](WorkerId w) { work(w); }) {}

  const FrameStats& run_frame(ItemFunctionRef process) override {
    process_ = &process;
    next_ = 0;  // published to the workers by the team's release (T1)
    for (auto& s : slots_) s.stats = {};
    const std::int64_t wall_ns = team_.run_frame();
    return collect(stats_, slots_, wall_ns, &team_.spans());
  }
  WorkerId worker_count() const noexcept override { return team_.size(); }
  ItemId grain() const noexcept { return grain_; }

 private:
  void work(WorkerId w) {
    WorkerSlot& me = slots_[w];
    for (;;) {
      if (!mutex_.try_lock()) {
        ++me.stats.lock_waits;
        const Clock::time_point start = Clock::now();
        mutex_.lock();
        me.stats.lock_wait_ns += nanoseconds_since(start);
      }
      const ItemId first = next_;
      const ItemId last = static_cast<ItemId>(std::min<std::uint64_t>(std::uint64_t{first} + grain_, items_));
      next_ = last;
      mutex_.unlock();
      if (first >= last) return;
      me.run_range(*process_, first, last, w, timed_);
    }
  }

  ItemId items_;
  ItemId grain_;
  bool timed_;
  std::mutex mutex_;
  ItemId next_ = 0;  // guarded by mutex_
  std::vector<WorkerSlot> slots_;
  const ItemFunctionRef* process_ = nullptr;
  FrameStats stats_;
  WorkerTeam team_;
};

}  // namespace frontsteal::sched
