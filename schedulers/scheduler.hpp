// scheduler.hpp — the one interface every scheduler implements: run one frame of N items over P workers.
//
// A frame calls process(item, worker) once for every item in [0, N) and returns when all calls have
// returned. Schedulers keep their threads (and whatever they learned) from frame to frame, as a renderer
// tessellating frame after frame would. If an item throws, every other item of the frame still runs; then
// run_frame throws ItemError (core/stealing_scheduler.hpp) naming the first failing item of the lowest
// worker. Statistics are per worker (core/frame_stats.hpp): busy time (time processing items, measured once
// per claim), steals, failed steals, lock waits. Utilization = busy / (wall × P), as in paper Table 1.
//
// What each scheduler is, and which fields of WorkerFrameStats it fills, is documented in registry.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/frame_stats.hpp"
#include "core/id_range.hpp"

namespace frontsteal::sched {

// A non-owning reference to the item function: one indirect call per item, the same for every scheduler.
class ItemFunctionRef {
 public:
  template <class F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, ItemFunctionRef>) ItemFunctionRef(F& f)
  noexcept  // NOLINT: implicit on purpose, so run_frame(lambda) reads naturally
      : object_(const_cast<void*>(static_cast<const void*>(&f))),
        call_([](void* o, ItemId id, WorkerId w) { (*static_cast<F*>(o))(id, w); }) {}
  void operator()(ItemId id, WorkerId w) const { call_(object_, id, w); }

 private:
  void* object_;
  void (*call_)(void*, ItemId, WorkerId);
};

// What a scheduler may know of the workload before the first frame. Static spatial partitions use it;
// everything else ignores it. Either vector may be empty (no spatial information / equal costs).
struct WorkloadHints {
  std::vector<std::array<double, 3>> centres;  // per item: a representative point (patch centre)
  std::vector<double> costs;                   // per item: estimated cost, any unit
};

struct SchedulerConfig {
  WorkerId workers = 2;
  ItemId items = 0;
  ItemId grain = 0;         // items per claim of chunked schedulers; 0 = the scheduler's default
  std::uint64_t seed = 1;   // victim orders, annealing
  bool time_claims = true;  // busy time per claim; false drops the clock reads (overhead microbenchmarks)
};

class Scheduler {
 public:
  virtual ~Scheduler() = default;
  virtual const FrameStats& run_frame(ItemFunctionRef process) = 0;
  virtual WorkerId worker_count() const noexcept = 0;
};

// Granularity of the global queue and the chunked counter (paper §4.1): N / (100 P), at least 1.
inline ItemId default_grain(ItemId items, WorkerId workers) {
  const ItemId g = items / (100 * std::max<WorkerId>(workers, 1));
  return g == 0 ? 1 : g;
}

// What the chunk-claiming peers (queue-mutex, chunked counter, moodycamel queue) share: [0, items) is handed
// out `grain` items per claim (default_grain unless the config sets one), and whether each claim's busy time
// is clocked.
struct ChunkClaims {
  explicit ChunkClaims(const SchedulerConfig& c)
      : items(c.items), grain(c.grain ? c.grain : default_grain(c.items, c.workers)), timed(c.time_claims) {}
  // The end of the chunk that starts at `first` (64-bit: a cursor P x grain past N cannot wrap).
  ItemId chunk_end(std::uint64_t first) const noexcept {
    return static_cast<ItemId>(std::min<std::uint64_t>(first + grain, items));
  }
  ItemId items;
  ItemId grain;
  bool timed;
};

}  // namespace frontsteal::sched
