// stealing_adapter.hpp — the core protocol (core/stealing_scheduler.hpp) behind the Scheduler interface, one
// instance per memory-order policy. It fills the steal counters itself (core/frame_loop.hpp).
#pragma once

#include "core/stealing_scheduler.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::sched {

template <class Policy>
class StealingAdapter final : public Scheduler {
 public:
  explicit StealingAdapter(const SchedulerConfig& config)
      : scheduler_({.workers = config.workers, .items = config.items, .seed = config.seed}) {}
  const FrameStats& run_frame(ItemFunctionRef process) override {
    return scheduler_.run_frame([process](ItemId id, WorkerId w) { process(id, w); });
  }
  WorkerId worker_count() const noexcept override { return scheduler_.worker_count(); }

 private:
  StealingScheduler<Policy, StdBackend> scheduler_;
};

}  // namespace frontsteal::sched
