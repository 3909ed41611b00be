// frame_loop.hpp — one frame of load stealing for every worker, and the boundary between frames.
//
// Based on paper §4.2.1: each worker runs its tessellation loop over its ActivityList, then steals until all
// workers are idle; the next frame starts from each worker's list at the end of this one (temporal
// coherence). This file holds the shared structure of all workers (StealingWorkers) and the per-worker frame
// procedure. It creates no threads: stealing_scheduler.hpp runs it on persistent std::threads, the model
// checker on Relacy threads, tests drive it from their own threads.
//
// ROLES
//   worker w     runs await_frame_start(w, k) then run_frame(w, k, f); uses only workers_[w] privately.
//   caller       releases frame k (E1) and waits for it to be done (E6); between frames it may reseed.
//   last arriver the worker whose arrival completes frame k: rebuilds the next allocation where the policy
//                is at-least-once (duplicates removed), installs every worker's list for frame k+1 (so all
//                lists are stealable from the first instant of the frame), re-arms termination (E4),
//                publishes done (E5).
//   observer     any other thread (a watchdog, stress/watchdog.hpp) may call debug_state() at any time: relaxed
//                atomic reads of the slots and counters, outside every labelled site, so it neither orders nor
//                perturbs anything; what it returns is a racy, diagnostic picture (workers_snapshot.hpp).
//
// OWNERSHIP
//   Worker (owner, thief, log, next_list, stats, failure)   its worker's thread during a frame; the caller
//                                                            (reseed) and the last arriver between frames
//   every ActivitySlot's list                                installed between frames by the last arriver or
//                                                            by reseed, while every worker waits (F1)
//   started_   caller writes (E1)            workers read (E2)
//   arrivals_  workers RMW (E3), monotonic: frame k is complete when it reaches k * P
//   done_      last arriver writes (E5)     caller and workers read (E6)
//
// INVARIANTS
//   F1  Frame k's work starts only after done_ >= k-1 and started_ >= k; so no thief of frame k-1 is still
//       looking at a list when frame k installs it, and the caller's reseed is visible (E1 -> E2).
//   F2  At the end of frame k the workers' next_lists partition [0, items): exactly-once policies by I4 of
//       stealing_protocol.hpp; at-least-once policies because the last arriver removes duplicates.
//
// ORDERS
//   E1 release -> E2 acquire (caller's reseed and item function visible to workers);
//   E3 acq_rel chain: every worker's frame (stats, next_list, item effects) happens-before the last arriver;
//   E4, E5 release -> E6 acquire: the caller sees every worker's results; the next frame sees active = P.
//
// LOSS ACCOUNT (frame_stats.hpp): each worker stamps the start of its first drain and the end of its last one
// (clock reads the busy time makes anyway), and with a SteadyPhaseTimer (phase_timer.hpp) also when each idle
// spell starts, when a steal's LockList is held and how long it waited at T4; the caller turns the stamps into
// wake-up and termination times against its own release and done (claim_span). None of it is on the owner's
// per-item path, and NoPhaseTimer removes every read the account adds.
#pragma once

#include <chrono>
#include <cstdint>
#include <exception>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/active_workers.hpp"
#include "core/activity_list.hpp"
#include "core/check.hpp"
#include "core/frame_stats.hpp"
#include "core/id_range.hpp"
#include "core/labelled_access.hpp"
#include "core/policies.hpp"
#include "core/phase_timer.hpp"
#include "core/stealing_protocol.hpp"
#include "core/thread_cpu_time.hpp"
#include "core/workers_snapshot.hpp"

namespace frontsteal {

// The first exception an item function threw on one worker in one frame.
struct ItemFailure {
  ItemId item = 0;
  WorkerId worker = 0;
  std::exception_ptr error;
};

// When worker w's claims started and its last items ended, in one frame (SteadyPhaseTimer's clock, ns; both 0
// when the worker never drained).
struct ClaimSpan {
  std::int64_t first_claim_at = 0;
  std::int64_t last_done_at = 0;
};

template <class Backend, class Policy, class Timer = SteadyPhaseTimer>
class StealingWorkers {
 public:
  using Slot = ActivitySlot<Backend, Policy>;
  using OwnerHandle = Owner<Backend, Policy>;
  using ThiefHandle = Thief<Backend, Policy>;

  // Lists start as contiguous blocks (block_allocation); reseed() replaces them between frames.
  StealingWorkers(WorkerId workers, ItemId items, std::uint64_t seed)
      : worker_count_(workers), item_count_(items), active_(workers) {
    if (workers == 0) throw std::invalid_argument("frontsteal: at least one worker is needed");
    const std::uint32_t max_entries = std::max<std::uint32_t>(items, 1);
    std::vector<RangeList> initial = block_allocation(items, workers);
    for (WorkerId w = 0; w < workers; ++w) {
      slots_.push_back(std::make_unique<Slot>(max_entries));
      workers_.push_back(std::make_unique<Worker>(*slots_.back(), active_, max_entries));
      Worker& me = *workers_.back();
      me.next_list = std::move(initial[w]);
      me.owner.install(me.next_list);
      me.log.reserve(max_entries);
      // Paper §4.2.1: "each processor maintains a list of other processors in a random order".
      for (WorkerId v = 0; v < workers; ++v) {
        if (v != w) me.victims.push_back(v);
      }
      std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + w);
      std::shuffle(me.victims.begin(), me.victims.end(), rng);
    }
    if (needs_dedupe()) seen_.assign(items, 0);
  }

  WorkerId worker_count() const noexcept { return worker_count_; }
  ItemId item_count() const noexcept { return item_count_; }

  // ---- caller side, between frames --------------------------------------------------------------------
  // Replaces every worker's next list (paper §3's static allocation, or any other). The lists must partition
  // [0, items); each keeps its order, with adjacent ranges merged. Throws std::invalid_argument otherwise.
  void reseed(const std::vector<RangeList>& allocation) {
    if (allocation.size() != worker_count_) {
      throw std::invalid_argument("frontsteal: reseed got " + std::to_string(allocation.size()) + " lists for " +
                                  std::to_string(worker_count_) + " workers");
    }
    if (!is_partition(allocation, item_count_)) {
      throw std::invalid_argument("frontsteal: reseed lists do not partition [0, " + std::to_string(item_count_) +
                                  "): an id is missing, repeated or out of range");
    }
    for (WorkerId w = 0; w < worker_count_; ++w) {
      RangeList merged;
      for (const IdRange& r : allocation[w]) append_merging(merged, r);
      A::write(workers_[w]->handover, std::uint32_t{0});
      workers_[w]->next_list = std::move(merged);
      workers_[w]->owner.install(workers_[w]->next_list);
    }
  }
  // Replaces worker w's victim order (harnesses use it to force a particular chain of steals). Between frames.
  void set_victims(WorkerId w, std::vector<WorkerId> victims) {
    for (WorkerId v : victims) {
      if (v == w || v >= worker_count_) throw std::invalid_argument("frontsteal: bad victim " + std::to_string(v));
    }
    A::write(workers_[w]->handover, std::uint32_t{0});
    workers_[w]->victims = std::move(victims);
    workers_[w]->victim_cursor = 0;
  }
  // How many positions each owner claims per handshake: 1 (the default) is try_claim, the paper's loop; n > 1
  // is Owner::try_claim_up_to(n), one O1-O4 for up to n items of one list entry. Between frames.
  void set_claim_batch(std::uint32_t n) {
    if (n == 0) throw std::invalid_argument("frontsteal: a claim batch of 0 items claims nothing");
    for (const auto& w : workers_) A::write(w->handover, std::uint32_t{0});
    claim_batch_ = n;
  }
  std::uint32_t claim_batch() const noexcept { return claim_batch_; }
  // Each worker's list for the next frame (between frames).
  std::vector<RangeList> allocation() const {
    std::vector<RangeList> out;
    for (const auto& w : workers_) {
      (void)A::read(w->handover);
      out.push_back(w->next_list);
    }
    return out;
  }

  void release_frame(std::uint32_t frame) noexcept {
    A::template store<Site::kFrameStart>(started_, frame);  // E1
    Backend::notify_all(started_);
  }
  void await_frame_done(std::uint32_t frame) noexcept { await_at_least(done_, frame); }

  // ---- worker side --------------------------------------------------------------------------------------
  void await_frame_start(std::uint32_t frame) noexcept {
    await_at_least(done_, frame - 1);  // E6: frame-1 is over for everyone (F1)
    for (std::uint32_t s = A::template load<Site::kFrameAwaitStart>(started_); s < frame;  // E2
         s = A::template load<Site::kFrameAwaitStart>(started_)) {
      A::template wait_while_equal<Site::kFrameAwaitStart>(started_, s);
    }
  }

  // Worker w's part of frame `frame` (frames are numbered 1, 2, ... without gaps). `process(id, w)` runs
  // once per claimed item; an exception it throws is recorded (first one per worker) and the frame goes on.
  template <class Process>
  void run_frame(WorkerId w, std::uint32_t frame, Process& process) {
    Worker& me = *workers_[w];
    A::write(me.handover, frame);  // the worker takes its fields over (ordered by E2/E6)
    me.stats = WorkerFrameStats{};
    me.failure.reset();
    const auto start = Clock::now();
    const std::int64_t cpu_start = thread_cpu_ns();  // once per frame: the clock is a system call
    me.log.clear();
    me.span = ClaimSpan{};
    for (;;) {
      drain(me, w, process);
      active_.leave();  // A2: our list is exhausted and every item we claimed is done
      const std::int64_t looking_since = Timer::now();
      if (!find_work(me)) break;  // the last search is the frame's end: termination, not search
      me.stats.search_ns += me.steal_locked_at - looking_since;
    }
    me.next_list = normalized(me.log);  // sorted, adjacent ranges merged: lists do not fragment without bound
    me.stats.active_ns = elapsed_ns(start);
    me.stats.cpu_ns = thread_cpu_ns() - cpu_start;
    me.stats.idle_ns = me.stats.active_ns - me.stats.busy_ns;
    A::write(me.handover, frame);  // ... and hands them back (ordered by E3, then E5)
    arrive(frame);
  }

  // ---- observation and handles for tests --------------------------------------------------------------
  // Between frames only (the caller after await_frame_done).
  const WorkerFrameStats& stats(WorkerId w) const noexcept {
    (void)A::read(workers_[w]->handover);
    return workers_[w]->stats;
  }
  const std::optional<ItemFailure>& failure(WorkerId w) const noexcept {
    (void)A::read(workers_[w]->handover);
    return workers_[w]->failure;
  }
  // When worker w's first claim of the last frame started and its last items ended (between frames only).
  const ClaimSpan& claim_span(WorkerId w) const noexcept {
    (void)A::read(workers_[w]->handover);
    return workers_[w]->span;
  }
  OwnerHandle& owner(WorkerId w) noexcept { return workers_[w]->owner; }
  ThiefHandle& thief(WorkerId w) noexcept { return workers_[w]->thief; }
  Slot& slot(WorkerId w) noexcept { return *slots_[w]; }
  ActiveWorkers<Backend, Policy>& active() noexcept { return active_; }

  // ---- diagnostics (any thread, any time) --------------------------------------------------------------
  // Every worker's Front, End, ListTransient and LockList, the active count and the frame counters, read
  // with relaxed atomic loads (Access::peek): no labelled site, no order, no fence, so taking a snapshot does
  // not change the protocol it observes. Racy by design and not one consistent cut (workers_snapshot.hpp);
  // for watchdogs (stress/watchdog.hpp) and failure reports only. Needs a backend with peek (std, chaos).
  WorkersSnapshot debug_state() const {
    WorkersSnapshot s;
    s.workers.reserve(worker_count_);
    for (const auto& slot : slots_) {
      s.workers.push_back(
          {A::peek(slot->front), A::peek(slot->end), A::peek(slot->transient), slot->lock.debug_held()});
    }
    s.active = active_.debug_count();
    s.started = A::peek(started_);
    s.done = A::peek(done_);
    s.arrivals = A::peek(arrivals_);
    return s;
  }

 private:
  using A = Access<Backend, Policy>;
  using Clock = std::chrono::steady_clock;

  struct alignas(kCacheLine) Worker {
    Worker(Slot& slot, ActiveWorkers<Backend, Policy>& active, std::uint32_t max_entries)
        : owner(slot), thief(active, max_entries) {}
    // Stands for every plain field below when it changes hands between threads (the worker during a frame;
    // the caller and the last arriver between frames). Each such hand-over writes or reads this cell, so a
    // checking backend (Relacy) sees a race on it exactly when the hand-over of those fields is not ordered.
    // In production it is one plain store or load per hand-over.
    typename Backend::template Cell<std::uint32_t> handover{};
    OwnerHandle owner;
    ThiefHandle thief;
    RangeList log;        // ids claimed this frame, in claim order
    RangeList next_list;  // this worker's list for the next frame
    std::vector<WorkerId> victims;
    std::uint32_t victim_cursor = 0;
    WorkerFrameStats stats;
    std::optional<ItemFailure> failure;
    ClaimSpan span;                    // this frame's first drain start and last drain end
    std::int64_t steal_locked_at = 0;  // the last successful steal: when the victim's LockList was held
  };

  // The loss account's view of one steal attempt (NoStealObserver's interface): when the victim's LockList was
  // held, and how long the attempt waited at T4.
  struct StealClock {
    std::int64_t locked_at = 0, wait_from = 0, waited = 0;
    void locked() noexcept { locked_at = Timer::now(); }
    void wait_begins() noexcept { wait_from = Timer::now(); }
    void wait_over() noexcept {
      if (wait_from != 0) waited += Timer::now() - wait_from;
      wait_from = 0;
    }
  };

  static bool needs_dedupe() noexcept {
    return Policy::kContract == Contract::kAtLeastOnce || Policy::defects() != Defect::kNone;
  }

  static std::int64_t elapsed_ns(Clock::time_point since) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - since).count();
  }

  // The owner loop (paper §4.2.1 lines 1-5) over the current list.
  template <class Process>
  void drain(Worker& me, WorkerId w, Process& process) {
    const auto start = Clock::now();
    if (me.span.first_claim_at == 0) me.span.first_claim_at = steady_ns(start);
    if (claim_batch_ <= 1) {
      while (const std::optional<ItemId> id = me.owner.try_claim()) run_item(me, w, *id, process);
    } else {
      while (const std::optional<IdRange> ids = me.owner.try_claim_up_to(claim_batch_)) {
        for (ItemId id = ids->begin; id < ids->end; ++id) run_item(me, w, id, process);
      }
    }
    me.owner.log_claimed(me.log);
    const auto end = Clock::now();
    me.stats.busy_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(end - start).count();
    ++me.stats.claims;
    me.span.last_done_at = steady_ns(end);
  }

  template <class Process>
  void run_item(Worker& me, WorkerId w, ItemId id, Process& process) {
    ++me.stats.items_processed;
    try {
      process(id, w);
    } catch (...) {
      if (!me.failure) me.failure = ItemFailure{id, w, std::current_exception()};
    }
  }

  // The idle loop (paper §4.2.1 lines 61-68): victims in this worker's random order, each round starting one
  // further along. True when a share was installed; false when every worker is idle (the frame is over).
  bool find_work(Worker& me) noexcept {
    const auto n = static_cast<std::uint32_t>(me.victims.size());
    for (std::uint32_t spins = 0;; ++spins) {
      for (std::uint32_t i = 0; i < n; ++i) {
        const WorkerId v = me.victims[(me.victim_cursor + i) % n];
        ++me.stats.steal_attempts;
        StealClock clock;
        const StealOutcome outcome = me.thief.try_steal(*slots_[v], clock);
        me.stats.transient_wait_ns += clock.waited;  // inside this attempt: search's, or the steal's below
        switch (outcome) {
          case StealOutcome::kLockBusy: ++me.stats.steals_lock_busy; break;
          case StealOutcome::kEmpty: ++me.stats.steals_empty; break;
          case StealOutcome::kSkippedAll:
            ++me.stats.steals_skipped_all;
            me.stats.items_skipped += me.thief.skipped();
            break;
          case StealOutcome::kStolen:
            ++me.stats.steals_succeeded;
            me.stats.items_skipped += me.thief.skipped();
            me.stats.items_stolen += frontsteal::item_count(me.thief.share());
            me.owner.install(me.thief.share());
            me.victim_cursor = (me.victim_cursor + i + 1) % n;
            me.steal_locked_at = clock.locked_at;
            me.stats.steal_ns += Timer::now() - clock.locked_at;
            return true;
        }
      }
      if (n > 0) me.victim_cursor = (me.victim_cursor + 1) % n;
      if (active_.all_idle()) return false;  // A3
      Backend::spin_pause(Site::kActivePoll, spins);
    }
  }

  void arrive(std::uint32_t frame) {
    const std::uint64_t before = A::template fetch_add<Site::kFrameArrive>(arrivals_, std::uint64_t{1});  // E3
    if (before + 1 != std::uint64_t{frame} * worker_count_) return;
    // Last arriver: everyone else is done with frame `frame` and waits for done_.
    for (auto& w : workers_) A::write(w->handover, frame);  // the last arriver takes every worker's fields
    if (needs_dedupe()) remove_duplicates();
    // Install every list now rather than when each worker starts the next frame: a worker whose thread is
    // slow to wake (or preempted) then has its list stolen instead of holding the frame back.
    for (auto& w : workers_) w->owner.install(w->next_list);
    active_.rearm(worker_count_);                              // E4
    A::template store<Site::kFramePublishDone>(done_, frame);  // E5
    Backend::notify_all(done_);
  }

  // At-least-once policies can leave an id in two workers' logs; keep it with the lower worker id so the next
  // frame's lists stay a partition (F2). A missing id is a lost item: a protocol bug, never input; the
  // backend reports it (std: abort with a message; Relacy: a failed test with its history).
  void remove_duplicates() {
    std::fill(seen_.begin(), seen_.end(), std::uint8_t{0});
    for (auto& w : workers_) {
      RangeList kept;
      for (const IdRange& r : w->next_list) {
        for (ItemId i = r.begin; i < r.end; ++i) {
          if (seen_[i] == 0) {
            seen_[i] = 1;
            append_merging(kept, {i, i + 1});
          }
        }
      }
      w->next_list = std::move(kept);
    }
    for (ItemId i = 0; i < item_count_; ++i) {
      Backend::invariant(seen_[i] == 1, "frame end: an item is in no worker's log (lost)");
    }
  }

  template <class Atom>
  void await_at_least(const Atom& a, std::uint32_t target) noexcept {
    for (std::uint32_t d = A::template load<Site::kFrameAwaitDone>(a); d < target;  // E6
         d = A::template load<Site::kFrameAwaitDone>(a)) {
      A::template wait_while_equal<Site::kFrameAwaitDone>(a, d);
    }
  }

  const WorkerId worker_count_;
  const ItemId item_count_;
  std::uint32_t claim_batch_ = 1;  // positions per owner handshake (set_claim_batch)
  ActiveWorkers<Backend, Policy> active_;
  std::vector<std::unique_ptr<Slot>> slots_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::vector<std::uint8_t> seen_;  // remove_duplicates scratch, allocated once

  alignas(kCacheLine) typename Backend::template Atomic<std::uint32_t> started_{0u};
  alignas(kCacheLine) typename Backend::template Atomic<std::uint64_t> arrivals_{0u};
  alignas(kCacheLine) typename Backend::template Atomic<std::uint32_t> done_{0u};
};

}  // namespace frontsteal
