// tbb_scheduler.cpp — oneTBB parallel_for with affinity_partitioner (library_schedulers.hpp).
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <thread>

#include "core/thread_cpu_time.hpp"
#include "schedulers/library_schedulers.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {
namespace {

class TbbAffinityScheduler final : public Scheduler {
 public:
  explicit TbbAffinityScheduler(const SchedulerConfig& config)
      : items_(config.items),
        grain_(config.grain ? config.grain : 1),
        timed_(config.time_claims),
        // TBB caps its workers at the hardware threads unless told otherwise; P above that (oversubscription)
        // needs the cap raised, or the arena would silently run with fewer threads than asked for.
        parallelism_(tbb::global_control::max_allowed_parallelism,
                     std::max<std::size_t>(config.workers, std::thread::hardware_concurrency())),
        arena_(static_cast<int>(config.workers), 1),
        slots_(config.workers) {}

  const FrameStats& run_frame(ItemFunctionRef process) override {
    for (auto& s : slots_) s.stats = {};
    const Clock::time_point start = Clock::now();
    arena_.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<ItemId>(0, items_, grain_),
          [&](const tbb::blocked_range<ItemId>& r) {
            const int slot = tbb::this_task_arena::current_thread_index();
            const auto w = static_cast<WorkerId>(slot);
            // oneTBB's threads enter and leave the arena as they please, so there is no per-frame span to
            // time: CPU time is read around each claimed range instead (affinity_partitioner claims a few
            // dozen ranges per thread and frame on a quiet machine, so the system-call clock costs little),
            // and active_ns is the claims' busy time itself, so active − cpu is the time descheduled while
            // holding work. Not a separate wall clock around the CPU-clock reads: on a loaded machine the
            // partitioner splits into many more ranges, and a preemption landing at a system call's return
            // would then count as "active" outside every claim.
            WorkerFrameStats& stats = slots_[w].stats;
            const std::int64_t busy_before = stats.busy_ns;
            const std::int64_t cpu_start = thread_cpu_ns();
            slots_[w].run_range(process, r.begin(), r.end(), w, timed_);
            stats.cpu_ns += thread_cpu_ns() - cpu_start;
            stats.active_ns += stats.busy_ns - busy_before;
          },
          partitioner_);
    });
    return collect(stats_, slots_, nanoseconds_since(start));
  }
  WorkerId worker_count() const noexcept override { return static_cast<WorkerId>(slots_.size()); }

 private:
  ItemId items_;
  ItemId grain_;
  bool timed_;
  tbb::global_control parallelism_;
  tbb::task_arena arena_;
  tbb::affinity_partitioner partitioner_;
  std::vector<WorkerSlot> slots_;
  FrameStats stats_;
};

}  // namespace

std::unique_ptr<Scheduler> make_tbb_affinity_scheduler(const SchedulerConfig& config) {
  if (config.workers == 0) throw std::invalid_argument("frontsteal: at least one worker is needed");
  return std::make_unique<TbbAffinityScheduler>(config);
}

}  // namespace frontsteal::sched
