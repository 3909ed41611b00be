// stealing_adapter.hpp — the core protocol (core/stealing_scheduler.hpp) behind the Scheduler interface, one
// instance per memory-order policy (and phase timer: core/phase_timer.hpp). It fills the steal counters and the
// loss account's phase times itself (core/frame_loop.hpp).
#pragma once

#include "core/stealing_scheduler.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::sched {

template <class Policy, class Timer = SteadyPhaseTimer>
class StealingAdapter final : public Scheduler {
 public:
  explicit StealingAdapter(const SchedulerConfig& config, bool caller_works = false)
      : scheduler_(
            {.workers = config.workers, .items = config.items, .seed = config.seed, .caller_works = caller_works}) {}
  const FrameStats& run_frame(ItemFunctionRef process) override {
    return scheduler_.run_frame([process](ItemId id, WorkerId w) { process(id, w); });
  }
  WorkerId worker_count() const noexcept override { return scheduler_.worker_count(); }

 private:
  StealingScheduler<Policy, StdBackend, Timer> scheduler_;
};

}  // namespace frontsteal::sched
