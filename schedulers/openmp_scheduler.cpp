// openmp_scheduler.cpp — OpenMP schedule(dynamic, grain) (library_schedulers.hpp), grain N / (100 P) unless the
// config sets one: the chunk every scheduler that claims from a shared cursor gets (paper §4.1). OpenMP's own
// default is 1, where every item's claim is a fetch_add on the team's counter, whose line then moves between the
// cores (~0.2 us per item at P = 2 on these VMs); registry.hpp keeps that as openmp-dynamic:chunk1. The loop runs
// over chunk indices with schedule(dynamic, 1): the same claims as schedule(dynamic, grain) over items. Busy time is
// each thread's run of claims, from its first claim to the end of the loop (WorkerSlot::begin_run): timing each claim
// of one item would add two clock reads (~100 ns here) to every item, which a program using OpenMP does not pay.
//
// Each instance opens its parallel regions from a thread of its own (the driver), not from the caller. libgomp
// keeps one thread pool per thread that opens a region, and when a region asks for fewer threads than the last
// one it ends the pool's surplus threads; the next larger region creates them again. A caller that runs teams of
// several sizes (the main job's rounds alternate P = 2, 4, 8, 16 on one thread) would so pay thread creation, and
// the first touch of the new threads' memory, in the first frame after every change of P: measured on a 16-core
// machine, 39–59 ms for that frame at P = 16 against 5.3 ms for the next. An application runs a fixed team;
// the driver gives each instance one, created by its untimed warm-up frame. The caller's hand-off to the driver
// and back (two futex wake-ups) is inside the timed frame, as the other teams' wake-ups are.
#include <omp.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "schedulers/library_schedulers.hpp"
#include "core/thread_cpu_time.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {
namespace {

class OpenMpDynamicScheduler final : public Scheduler {
 public:
  explicit OpenMpDynamicScheduler(const SchedulerConfig& config)
      : items_(config.items),
        grain_(config.grain ? config.grain : default_grain(config.items, config.workers)),
        timed_(config.time_claims),
        slots_(config.workers),
        driver_([this] { drive(); }) {}

  ~OpenMpDynamicScheduler() override {
    stop_.store(true, std::memory_order_relaxed);
    requested_.fetch_add(1, std::memory_order_release);
    requested_.notify_one();
    driver_.join();  // libgomp ends the driver's pool with it
  }

  const FrameStats& run_frame(ItemFunctionRef process) override {
    for (auto& s : slots_) s.begin_frame();
    const Clock::time_point start = Clock::now();
    process_ = &process;
    const std::uint64_t frame = requested_.fetch_add(1, std::memory_order_release) + 1;
    requested_.notify_one();
    for (std::uint64_t seen = done_.load(std::memory_order_acquire); seen != frame;
         seen = done_.load(std::memory_order_acquire)) {
      done_.wait(seen, std::memory_order_acquire);
    }
    return collect(stats_, slots_, {start, Clock::now()});
  }
  WorkerId worker_count() const noexcept override { return static_cast<WorkerId>(slots_.size()); }

 private:
  // The driver: one parallel region per requested frame, then the frame's number in done_.
  void drive() {
    std::uint64_t served = 0;
    for (;;) {
      requested_.wait(served, std::memory_order_acquire);
      const std::uint64_t frame = requested_.load(std::memory_order_acquire);
      if (stop_.load(std::memory_order_relaxed)) return;
      for (; served != frame; ++served) run_region(*process_);
      done_.store(frame, std::memory_order_release);
      done_.notify_one();
    }
  }

  void run_region(ItemFunctionRef process) {
    const long long chunks = (static_cast<long long>(items_) + grain_ - 1) / grain_;
    const int workers = static_cast<int>(slots_.size());
#pragma omp parallel num_threads(workers)
    {
      const auto w = static_cast<WorkerId>(omp_get_thread_num());
      WorkerSlot& me = slots_[w];
      // Each thread's span: from entering the region to leaving the loop (nowait), before the region's closing
      // barrier, where libgomp spins and then sleeps: that wait is not part of the frame's work.
      const Clock::time_point span_start = Clock::now();
      const std::int64_t cpu_start = thread_cpu_ns();
      bool claimed = false;
#pragma omp for schedule(dynamic, 1) nowait
      for (long long c = 0; c < chunks; ++c) {
        if (!claimed) {
          me.begin_run(timed_);
          claimed = true;
        }
        const auto first = static_cast<ItemId>(c * grain_);
        const auto last = static_cast<ItemId>(std::min<long long>((c + 1) * grain_, items_));
        for (ItemId id = first; id < last; ++id) me.run(process, id, w);
      }
      if (claimed) me.end_run(timed_);
      me.stats.active_ns = nanoseconds_since(span_start);
      me.stats.cpu_ns = thread_cpu_ns() - cpu_start;
    }
  }

  ItemId items_;
  ItemId grain_;
  bool timed_;
  std::vector<WorkerSlot> slots_;
  FrameStats stats_;
  ItemFunctionRef* process_ = nullptr;       // the caller's, for the frame in flight (written before requested_)
  std::atomic<std::uint64_t> requested_{0};  // frames asked for (release: process_ and the slots' reset)
  std::atomic<std::uint64_t> done_{0};       // frames finished (release: the slots' stats)
  std::atomic<bool> stop_{false};
  std::thread driver_;  // last: it starts once every member above exists
};

}  // namespace

std::unique_ptr<Scheduler> make_openmp_dynamic_scheduler(const SchedulerConfig& config) {
  if (config.workers == 0) throw std::invalid_argument("frontsteal: at least one worker is needed");
  return std::make_unique<OpenMpDynamicScheduler>(config);
}

}  // namespace frontsteal::sched
