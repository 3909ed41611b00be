// chunked_counter_scheduler.hpp — self-scheduling with one atomic counter: a worker claims `grain` items with
// one fetch_add (default N / (100 P), the global queue's granularity, so the pair isolates lock against
// atomic). This is what OpenMP's schedule(dynamic, chunk) does inside libgomp; openmp_scheduler.cpp is the
// real thing.
//
// ORDERS: the fetch_add is relaxed: it only has to hand out disjoint ranges (atomicity of one RMW on one
// location); the frame's start and end (worker_team.hpp T1..T4) order everything else.
#pragma once

#include <atomic>

#include "schedulers/scheduler.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {

class ChunkedCounterScheduler final : public Scheduler {
 public:
  explicit ChunkedCounterScheduler(const SchedulerConfig& config)
      : items_(config.items),
        grain_(config.grain ? config.grain : default_grain(config.items, config.workers)),
        timed_(config.time_claims),
        slots_(config.workers),
        team_(config.workers, [this](WorkerId w) { work(w); }) {}

  const FrameStats& run_frame(ItemFunctionRef process) override {
    process_ = &process;
    next_.store(0, std::memory_order::relaxed);  // published by the team's release (T1)
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
      const std::uint64_t first = next_.fetch_add(grain_, std::memory_order::relaxed);
      if (first >= items_) return;
      const ItemId last = static_cast<ItemId>(std::min<std::uint64_t>(first + grain_, items_));
      me.run_range(*process_, static_cast<ItemId>(first), last, w, timed_);
    }
  }

  ItemId items_;
  ItemId grain_;
  bool timed_;
  alignas(64) std::atomic<std::uint64_t> next_{0};  // 64-bit: P × grain past N cannot wrap
  std::vector<WorkerSlot> slots_;
  const ItemFunctionRef* process_ = nullptr;
  FrameStats stats_;
  WorkerTeam team_;
};

}  // namespace frontsteal::sched
