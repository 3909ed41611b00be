// stealing_scheduler.hpp — the stealing protocol on persistent std::threads: run one frame at a time.
//
// Usage:
//   frontsteal::StealingScheduler<frontsteal::Fenced> s({.workers = 4, .items = n, .seed = 1});
//   const FrameStats& st = s.run_frame([&](ItemId id, WorkerId w) { tessellate(id); });
// Workers are threads created once that sleep between frames (futex); the caller releases a frame and waits.
// With caller_works the calling thread runs worker 0's part itself (as oneTBB and OpenMP do) and only workers
// 1 .. P-1 are threads: one wake-up less per frame. Measured by the main job against the default (paired rounds,
// 216 per P on a 2-vCPU VM) it was equivalent within +-2 % (P = 1: -0.4 % [-0.8, +0.0]; P = 2: +0.5 % [-0.7,
// +1.8]): the wake-up that costs is a sleeping vCPU's (0.5-0.6 ms there), which it does not remove. So it is
// an option, not the default (schedulers/registry.hpp: stealing/Fenced:caller-works).
// A frame returns when every item ran; if an item function threw, the frame still completes every other item and
// run_frame then throws ItemError naming the item. The next frame starts from each worker's list at the end of
// this one (paper §4.2.1).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "core/frame_loop.hpp"
#include "core/frame_stats.hpp"
#include "core/membarrier.hpp"
#include "core/phase_timer.hpp"
#include "core/std_backend.hpp"

namespace frontsteal {

// Thrown by run_frame after a frame in which an item function threw.
class ItemError : public std::runtime_error {
 public:
  ItemError(ItemId item, WorkerId worker, std::exception_ptr cause)
      : std::runtime_error(describe(item, worker, cause)), item_(item), worker_(worker), cause_(cause) {}
  ItemId item() const noexcept { return item_; }
  WorkerId worker() const noexcept { return worker_; }
  std::exception_ptr cause() const noexcept { return cause_; }

 private:
  static std::string describe(ItemId item, WorkerId worker, const std::exception_ptr& cause) {
    std::string what = "unknown exception";
    try {
      if (cause) std::rethrow_exception(cause);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    return "frontsteal: item " + std::to_string(item) + " failed on worker " + std::to_string(worker) + ": " + what;
  }
  ItemId item_;
  WorkerId worker_;
  std::exception_ptr cause_;
};

struct SchedulerOptions {
  WorkerId workers = 2;
  ItemId items = 0;
  std::uint64_t seed = 1;         // victim orders; the same seed gives the same orders
  bool caller_works = false;      // the calling thread runs worker 0's part of each frame (see above)
  std::uint32_t claim_batch = 1;  // items per owner handshake: 1 is the paper's loop (StealingWorkers::set_claim_batch)
};

// Timer: SteadyPhaseTimer fills the loss account's phase times (frame_stats.hpp); NoPhaseTimer leaves search,
// steal and wait at 0 and adds no clock read (wake-up and termination come from reads made anyway).
template <class Policy, class Backend = StdBackend, class Timer = SteadyPhaseTimer>
class StealingScheduler {
 public:
  explicit StealingScheduler(const SchedulerOptions& options)
      : core_((require_fences(), options.workers), options.items, options.seed), caller_works_(options.caller_works) {
    core_.set_claim_batch(options.claim_batch);
    threads_.reserve(options.workers);
    for (WorkerId w = caller_works_ ? 1 : 0; w < options.workers; ++w) {
      threads_.emplace_back([this, w] { worker_main(w); });
    }
  }
  StealingScheduler(const StealingScheduler&) = delete;
  StealingScheduler& operator=(const StealingScheduler&) = delete;

  ~StealingScheduler() {
    stop_.store(true, std::memory_order::relaxed);  // ordered before the workers' read by E1 -> E2
    core_.release_frame(frame_ + 1);
    for (auto& t : threads_) t.join();
  }

  // Runs one frame: process(id, worker) once per item (exactly once for exactly-once policies).
  template <class Process>
  const FrameStats& run_frame(Process&& process) {
    using Fn = std::remove_reference_t<Process>;
    process_ = ItemFunction{const_cast<void*>(static_cast<const void*>(&process)),
                            [](void* f, ItemId id, WorkerId w) { (*static_cast<Fn*>(f))(id, w); }};
    ++frame_;
    const auto start = std::chrono::steady_clock::now();
    core_.release_frame(frame_);
    if (caller_works_) {
      core_.await_frame_start(frame_);  // returns at once: this thread saw frame-1 done and released this one
      core_.run_frame(0, frame_, process_);
    }
    core_.await_frame_done(frame_);
    const auto done = std::chrono::steady_clock::now();
    last_.frame = frame_;
    last_.wall_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(done - start).count();
    last_.phases_timed = Timer::kOn;
    last_.workers.resize(core_.worker_count());
    for (WorkerId w = 0; w < core_.worker_count(); ++w) {
      WorkerFrameStats& ws = last_.workers[w] = core_.stats(w);
      // The account's ends, against this caller's release and done (the same clock the workers stamped with).
      const ClaimSpan& span = core_.claim_span(w);
      if (span.first_claim_at != 0) {
        ws.wake_ns = span.first_claim_at - steady_ns(start);
        ws.termination_ns = steady_ns(done) - span.last_done_at;
      }
    }
    for (WorkerId w = 0; w < core_.worker_count(); ++w) {
      if (const auto& f = core_.failure(w)) throw ItemError(f->item, f->worker, f->error);
    }
    return last_;
  }

  void reseed(const std::vector<RangeList>& allocation) { core_.reseed(allocation); }
  std::vector<RangeList> allocation() const { return core_.allocation(); }
  const FrameStats& last_frame() const noexcept { return last_; }
  WorkerId worker_count() const noexcept { return core_.worker_count(); }
  ItemId item_count() const noexcept { return core_.item_count(); }
  std::uint32_t frames_run() const noexcept { return frame_; }
  // Diagnostics from any thread, e.g. a watchdog's (stress/watchdog.hpp): see StealingWorkers::debug_state.
  WorkersSnapshot debug_state() const { return core_.debug_state(); }

 private:
  struct ItemFunction {
    void* object = nullptr;
    void (*call)(void*, ItemId, WorkerId) = nullptr;
    void operator()(ItemId id, WorkerId w) const { call(object, id, w); }
  };

  static int require_fences() {
    if constexpr (Policy::kNeedsMembarrier) {
      const MembarrierStatus& s = membarrier_status();
      if (!s.available) {
        throw std::runtime_error("frontsteal: policy " + std::string(Policy::kName) +
                                 " needs membarrier(PRIVATE_EXPEDITED), which is unavailable here (" + s.detail +
                                 "); use the Fenced policy instead");
      }
    }
    return 0;
  }

  void worker_main(WorkerId w) {
    for (std::uint32_t k = 1;; ++k) {
      core_.await_frame_start(k);
      if (stop_.load(std::memory_order::relaxed)) return;
      core_.run_frame(w, k, process_);
    }
  }

  StealingWorkers<Backend, Policy, Timer> core_;
  bool caller_works_;
  ItemFunction process_;
  std::uint32_t frame_ = 0;
  std::atomic<bool> stop_{false};
  FrameStats last_;
  std::vector<std::thread> threads_;
};

}  // namespace frontsteal
