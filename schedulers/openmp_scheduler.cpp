// openmp_scheduler.cpp — OpenMP schedule(dynamic, grain) (library_schedulers.hpp). The loop runs over chunk
// indices with schedule(dynamic, 1): the same claims as schedule(dynamic, grain) over items, and it lets us
// time each claim once.
#include <omp.h>

#include "schedulers/library_schedulers.hpp"
#include "core/thread_cpu_time.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {
namespace {

class OpenMpDynamicScheduler final : public Scheduler {
 public:
  explicit OpenMpDynamicScheduler(const SchedulerConfig& config)
      : items_(config.items),
        grain_(config.grain ? config.grain : 1),
        timed_(config.time_claims),
        slots_(config.workers) {}

  const FrameStats& run_frame(ItemFunctionRef process) override {
    for (auto& s : slots_) s.stats = {};
    const long long chunks = (static_cast<long long>(items_) + grain_ - 1) / grain_;
    const int workers = static_cast<int>(slots_.size());
    const Clock::time_point start = Clock::now();
#pragma omp parallel num_threads(workers)
    {
      const auto w = static_cast<WorkerId>(omp_get_thread_num());
      WorkerSlot& me = slots_[w];
      // Each thread's span: from entering the region to leaving the loop (nowait), before the region's closing
      // barrier, where libgomp spins and then sleeps: that wait is not part of the frame's work.
      const Clock::time_point span_start = Clock::now();
      const std::int64_t cpu_start = thread_cpu_ns();
#pragma omp for schedule(dynamic, 1) nowait
      for (long long c = 0; c < chunks; ++c) {
        const auto first = static_cast<ItemId>(c * grain_);
        const auto last = static_cast<ItemId>(std::min<long long>((c + 1) * grain_, items_));
        me.run_range(process, first, last, w, timed_);
      }
      me.stats.active_ns = nanoseconds_since(span_start);
      me.stats.cpu_ns = thread_cpu_ns() - cpu_start;
    }
    return collect(stats_, slots_, nanoseconds_since(start));
  }
  WorkerId worker_count() const noexcept override { return static_cast<WorkerId>(slots_.size()); }

 private:
  ItemId items_;
  ItemId grain_;
  bool timed_;
  std::vector<WorkerSlot> slots_;
  FrameStats stats_;
};

}  // namespace

std::unique_ptr<Scheduler> make_openmp_dynamic_scheduler(const SchedulerConfig& config) {
  if (config.workers == 0) throw std::invalid_argument("frontsteal: at least one worker is needed");
  return std::make_unique<OpenMpDynamicScheduler>(config);
}

}  // namespace frontsteal::sched
