// concurrent_queue_scheduler.hpp — the global queue of §4.1 without its lock: moodycamel::ConcurrentQueue
// (Debian libconcurrentqueue-dev, header-only) holding the frame's chunks, `grain` items each (default
// N / (100 P), as queue-mutex), so "locked queue vs stealing" is also asked against the best-known unlocked
// MPMC queue.
//
// PER FRAME
//   caller    refills the queue with the first item of every chunk (one enqueue_bulk through the scheduler's
//             producer token), then publishes the frame (worker_team.hpp T1).
//   worker w  try_dequeue(its consumer token) until it fails; runs [first, min(first + grain, N)) each time.
// Nothing is enqueued while workers dequeue (the refill happens before T1, and the previous frame's dequeues
// happen before the refill through T3 -> T4), so a failed try_dequeue means every chunk is claimed: with one
// producer, moodycamel's dequeue counters hand out each index below the tail exactly once, and a dequeue
// fails only once all of them are taken. The queue is empty at the end of every frame; its blocks are kept
// and reused by the next refill (no allocation in steady state once the first frame has sized it).
//
// TOKENS, AND WHY THESE (fairness): moodycamel keeps one FIFO sub-queue per producer, and a consumer token
// sticks to one producer for up to 256 dequeues before rotating. With ONE producer (the caller, through an
// explicit ProducerToken kept across frames) there is one sub-queue: every worker's dequeue is one fetch_add
// on its head, so chunks leave in index order to whichever worker asks first — exactly queue-mutex's shared
// cursor, minus the lock, which is the comparison we want. Refilling from the workers instead (each its own
// producer) would make consumer tokens prefer "their" sub-queue: static ranges with stealing by rotation, a
// different scheduler (that is openmp-static-steal's design). Consumer tokens are used (one per worker, made
// once) because they skip the producer search of the tokenless dequeue; with a single producer they change
// no order, only cost. An implicit producer (enqueue without a token) would free and re-take blocks through
// a thread-local lookup every frame; the explicit token keeps its block ring.
//
// Counters: busy per claim, as queue-mutex; there is no lock to wait on, and no steals.
// TSan: the header is plain std::atomic code compiled into our translation units, so ThreadSanitizer sees all
// of it (unlike libgomp or oneTBB); its acquire fences (e.g. the producer's is_empty check before reusing a
// block) are invisible to TSan, but in this use the block reuse is ordered by the team's frame barrier (T3 ->
// T4 -> refill), so the stress tier runs it under TSan (registry tsan_clean = true) with an empty suppression
// file.
#pragma once

#include <algorithm>
#include <concurrentqueue/concurrentqueue.h>
#include <memory>
#include <vector>

#include "schedulers/scheduler.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {

class ConcurrentQueueScheduler final : public Scheduler {
 public:
  explicit ConcurrentQueueScheduler(const SchedulerConfig& config)
      : claims_(config), queue_(chunk_count()), producer_(queue_), slots_(config.workers) {
    chunks_.reserve(chunk_count());
    for (ItemId first = 0; first < claims_.items; first = claims_.chunk_end(first)) {
      chunks_.push_back(first);
    }
    consumers_.reserve(config.workers);
    for (WorkerId w = 0; w < config.workers; ++w)
      consumers_.push_back(std::make_unique<moodycamel::ConsumerToken>(queue_));
    team_.emplace(config.workers, [this](WorkerId w) { work(w); });
  }
  ~ConcurrentQueueScheduler() override { team_.reset(); }  // threads first: they use the tokens and the queue

  const FrameStats& run_frame(ItemFunctionRef process) override {
    process_ = &process;
    for (auto& s : slots_) s.begin_frame();
    // Refill: published to the workers by the team's release (T1).
    if (!chunks_.empty() && !queue_.enqueue_bulk(producer_, chunks_.begin(), chunks_.size())) {
      throw std::bad_alloc();
    }
    const FrameWindow window = team_->run_frame();
    return collect(stats_, slots_, window, &team_->spans());
  }
  WorkerId worker_count() const noexcept override { return team_->size(); }
  ItemId grain() const noexcept { return claims_.grain; }

 private:
  std::size_t chunk_count() const {
    return claims_.grain ? (std::size_t{claims_.items} + claims_.grain - 1) / claims_.grain : 0;
  }

  void work(WorkerId w) {
    WorkerSlot& me = slots_[w];
    moodycamel::ConsumerToken& token = *consumers_[w];
    ItemId first = 0;
    while (queue_.try_dequeue(token, first)) {
      me.run_range(*process_, first, claims_.chunk_end(first), w, claims_.timed);
    }
  }

  ChunkClaims claims_;
  std::vector<ItemId> chunks_;  // the first item of every chunk, in order: the refill of every frame
  moodycamel::ConcurrentQueue<ItemId> queue_;
  moodycamel::ProducerToken producer_;                                 // used by the caller only, between frames
  std::vector<std::unique_ptr<moodycamel::ConsumerToken>> consumers_;  // [w]: used by worker w only
  std::vector<WorkerSlot> slots_;
  const ItemFunctionRef* process_ = nullptr;
  FrameStats stats_;
  std::optional<WorkerTeam> team_;  // last: its threads start once everything above exists
};

}  // namespace frontsteal::sched
