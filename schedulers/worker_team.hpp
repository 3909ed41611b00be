// worker_team.hpp — P persistent threads that run one frame at a time: the skeleton of every scheduler in
// schedulers/ that owns its threads (static, global queue, chunked counter, Chase–Lev). Those schedulers
// share run_frame and their per-worker slots through team_scheduler.hpp.
//
// ROLES
//   caller    run_frame(): publishes frame k (T1), sleeps until all P workers have arrived (T4), collects.
//   worker w  sleeps until frame k is published (T2), runs body(w), arrives (T3).
// OWNERSHIP
//   slots_[w] (stats, first failure)   worker w during a frame; the caller between frames
// ORDERS
//   T1 release (started_) -> T2 acquire: the caller's per-frame state (item function, scheduler state it
//      prepared) is visible to every worker.
//   T3 acq_rel chain on arrived_ -> T4 acquire: every worker's item effects and slot are visible to the
//      caller, and to the next frame's workers through T1.
// Sleeping is C++20 atomic wait/notify (a futex on Linux), as in core/stealing_scheduler.hpp, so every
// scheduler pays the same wake-up cost per frame.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

#include "core/frame_loop.hpp"
#include "core/frame_stats.hpp"
#include "core/phase_timer.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/thread_cpu_time.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::sched {

using Clock = std::chrono::steady_clock;

inline std::int64_t nanoseconds_since(Clock::time_point start) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count();
}

// The caller's view of one frame: from just before the release to just after it saw the frame done.
struct FrameWindow {
  Clock::time_point release, done;
  std::int64_t ns() const { return std::chrono::duration_cast<std::chrono::nanoseconds>(done - release).count(); }
};

// What one worker gathers in one frame; a cache line of its own.
struct alignas(64) WorkerSlot {
  WorkerFrameStats stats;
  std::optional<ItemFailure> failure;
  Clock::time_point run_start_{};  // begin_run's start
  // The start of this frame's first timed claim and the end of its last (0: none yet): the loss account's
  // wake-up and termination, from the clock reads the busy time makes anyway.
  std::int64_t first_claim_at = 0, last_done_at = 0;

  void begin_frame() {
    stats = {};
    first_claim_at = last_done_at = 0;
  }
  // One timed claim [start, end): its busy time and the account's ends.
  void add_claim(Clock::time_point start, Clock::time_point end) {
    stats.busy_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count();
    ++stats.claims;
    if (first_claim_at == 0) first_claim_at = steady_ns(start);
    last_done_at = steady_ns(end);
  }

  // Runs one item; an exception is recorded (the first one only) and the frame goes on.
  void run(ItemFunctionRef process, ItemId id, WorkerId w) {
    try {
      process(id, w);
    } catch (...) {
      if (!failure) failure = ItemFailure{id, w, std::current_exception()};
    }
    ++stats.items_processed;
  }
  // A run of claims timed as one, for schedulers whose claims are single items (OpenMP's dynamic,1; Chase-Lev's
  // leaves): two clock reads per item would cost ~100 ns here, more than the claim itself, so the busy time is the
  // run's, with the claims between its items inside it, as the stealing protocol's drain is.
  void begin_run(bool timed) {
    if (timed) run_start_ = Clock::now();
  }
  void end_run(bool timed) {
    if (timed) add_claim(run_start_, Clock::now());
  }
  // Runs [first, last) and adds it as a claim (add_claim) when `timed`.
  void run_range(ItemFunctionRef process, ItemId first, ItemId last, WorkerId w, bool timed) {
    const Clock::time_point start = timed ? Clock::now() : Clock::time_point{};
    for (ItemId id = first; id < last; ++id) run(process, id, w);
    if (timed) add_claim(start, Clock::now());
  }
};

// One worker's part of a frame, measured by whoever runs it: wall time and thread CPU time of the span.
struct alignas(64) WorkerSpan {
  std::int64_t active_ns = 0;
  std::int64_t cpu_ns = 0;
};

// Gathers the slots into a FrameStats and throws ItemError for the first recorded failure. `spans`, when
// given (one per slot), supplies active_ns and cpu_ns; otherwise the slots carry their own (OpenMP, oneTBB).
// Wake-up and termination are the slots' first and last claims against the caller's window.
inline const FrameStats& collect(FrameStats& out, std::vector<WorkerSlot>& slots, const FrameWindow& window,
                                 const std::vector<WorkerSpan>* spans = nullptr) {
  ++out.frame;
  const std::int64_t wall_ns = window.ns();
  out.wall_ns = wall_ns;
  out.workers.resize(slots.size());
  for (std::size_t w = 0; w < slots.size(); ++w) {
    out.workers[w] = slots[w].stats;
    out.workers[w].idle_ns = wall_ns - slots[w].stats.busy_ns;
    if (slots[w].first_claim_at != 0) {
      out.workers[w].wake_ns = slots[w].first_claim_at - steady_ns(window.release);
      out.workers[w].termination_ns = steady_ns(window.done) - slots[w].last_done_at;
    }
    if (spans) {
      out.workers[w].active_ns = (*spans)[w].active_ns;
      out.workers[w].cpu_ns = (*spans)[w].cpu_ns;
    }
  }
  for (auto& s : slots) {
    if (s.failure) {
      const ItemFailure f = *s.failure;
      for (auto& t : slots) t.failure.reset();
      throw ItemError(f.item, f.worker, f.error);
    }
  }
  return out;
}

class WorkerTeam {
 public:
  using Body = std::function<void(WorkerId)>;

  WorkerTeam(WorkerId workers, Body body) : workers_(workers), body_(std::move(body)), spans_(workers) {
    if (workers == 0) throw std::invalid_argument("frontsteal: at least one worker is needed");
    threads_.reserve(workers);
    for (WorkerId w = 0; w < workers; ++w) threads_.emplace_back([this, w] { worker_main(w); });
  }
  WorkerTeam(const WorkerTeam&) = delete;
  WorkerTeam& operator=(const WorkerTeam&) = delete;
  ~WorkerTeam() {
    stop_.store(true, std::memory_order::relaxed);  // ordered before the workers' read by T1 -> T2
    publish(frame_ + 1);
    for (auto& t : threads_) t.join();
  }

  // Runs body(w) on every worker once; returns the caller's window, from the release to the last arrival.
  FrameWindow run_frame() {
    const Clock::time_point start = Clock::now();
    publish(++frame_);
    const std::uint64_t target = std::uint64_t{frame_} * workers_;
    for (std::uint64_t a = arrived_.load(std::memory_order::acquire); a < target;
         a = arrived_.load(std::memory_order::acquire)) {
      arrived_.wait(a, std::memory_order::acquire);  // T4
    }
    return {start, Clock::now()};
  }
  WorkerId size() const noexcept { return workers_; }
  // Per worker, its part of the last frame (read by the caller after run_frame: ordered by T3 -> T4).
  const std::vector<WorkerSpan>& spans() const noexcept { return spans_; }

 private:
  void publish(std::uint32_t k) {
    started_.store(k, std::memory_order::release);  // T1
    started_.notify_all();
  }
  void worker_main(WorkerId w) {
    for (std::uint32_t k = 1;; ++k) {
      for (std::uint32_t s = started_.load(std::memory_order::acquire); s < k;
           s = started_.load(std::memory_order::acquire)) {
        started_.wait(s, std::memory_order::acquire);  // T2
      }
      if (stop_.load(std::memory_order::relaxed)) return;
      // The span is timed here, once per frame, so every team-based scheduler reports CPU time the same way.
      const Clock::time_point start = Clock::now();
      const std::int64_t cpu_start = thread_cpu_ns();
      body_(w);
      spans_[w] = WorkerSpan{nanoseconds_since(start), thread_cpu_ns() - cpu_start};
      const std::uint64_t a = arrived_.fetch_add(1, std::memory_order::acq_rel) + 1;  // T3
      if (a == std::uint64_t{k} * workers_) arrived_.notify_all();
    }
  }

  WorkerId workers_;
  Body body_;
  std::uint32_t frame_ = 0;
  alignas(64) std::atomic<std::uint32_t> started_{0};
  alignas(64) std::atomic<std::uint64_t> arrived_{0};
  std::atomic<bool> stop_{false};
  std::vector<WorkerSpan> spans_;  // spans_[w]: written by worker w before T3
  std::vector<std::thread> threads_;
};

}  // namespace frontsteal::sched
