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
#include "schedulers/team_scheduler.hpp"

namespace frontsteal::sched {

class ChunkedCounterScheduler final : public TeamScheduler<ChunkedCounterScheduler> {
 public:
  explicit ChunkedCounterScheduler(const SchedulerConfig& config) : TeamScheduler(config.workers), claims_(config) {}

  ItemId grain() const noexcept { return claims_.grain; }

 private:
  friend class TeamScheduler<ChunkedCounterScheduler>;
  void begin_frame() { next_.store(0, std::memory_order::relaxed); }  // published by the team's release (T1)
  void work(WorkerId w) {
    WorkerSlot& me = slot(w);
    for (;;) {
      const std::uint64_t first = next_.fetch_add(claims_.grain, std::memory_order::relaxed);
      if (first >= claims_.items) return;
      me.run_range(process(), static_cast<ItemId>(first), claims_.chunk_end(first), w, claims_.timed);
    }
  }

  ChunkClaims claims_;
  alignas(64) std::atomic<std::uint64_t> next_{0};  // 64-bit: P × grain past N cannot wrap
};

}  // namespace frontsteal::sched
