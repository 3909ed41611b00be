// refill_budget.hpp — how much of its rank list a hier worker takes into its local list at once (a refill), when
// some of the items have no known cost. One rule for frontsteal-mpi (hierarchical_rank.cpp) and its model
// (rma_simulator.cpp).
//
// WHY. A refill takes items until they are worth about --chunk-us. Some items have no time the rank knows (the
// first frame; items a remote steal brought). Priced at a mean (--work-ns, or the rank's last frame), a chunk
// of them can be a hundred times the target where the cost concentrates, and work in a local list can be taken
// by the rank's own threads but not by other ranks: one rank's threads then run the frame's tail alone while
// every other rank waits (SIMULATED at 256 ranks x 16 threads on the cost cascade, 1 ms of work per worker:
// a first frame of 2.3 ms priced at the mean, 1.3 ms with this rule). So the rule measures before it commits,
// and never strands more than a share of the rank's list:
//   PRICE   an unknown item costs what this worker's last item of the frame took (consecutive ids are close in
//           space, so their costs are alike); before its first item of the frame, the whole target (one item).
//   GROWTH  a refill takes at most twice as many unknown items as the worker's previous refill took items (at
//           least 1): a worker that crosses from a light region into a heavy one commits to few heavy items.
//   SHARE   at most a (2 x threads)-th of the rank list's unclaimed items (at least 1), as guided
//           self-scheduling does (Polychronopoulos & Kuck, IEEE ToC 1987): what stays in the rank list is what
//           other ranks can steal.
// Items with a known cost are priced with it and are not capped: the seeded schedulers' refills are as before.
#pragma once

#include <algorithm>
#include <cstdint>

namespace frontsteal::mpi {

// What one worker remembers between its refills within a frame (reset at each frame's start).
struct RefillHistory {
  double last_item_ns = 0;        // the time of its last finished item this frame; 0 before the first
  std::uint32_t last_refill = 0;  // the items its last refill took this frame; 0 before the first
};

// One refill's admission: items are offered in list order, each with its known cost or none.
class RefillBudget {
 public:
  // `target_ns`: --chunk-us; `max_items`: the hard cap (kMaxChunk); `unclaimed`: the rank list's unclaimed
  // items when the refill starts; `threads`: the rank's workers.
  RefillBudget(double target_ns, std::uint32_t max_items, const RefillHistory& h, std::uint32_t unclaimed,
               std::uint32_t threads)
      : target_ns_(target_ns),
        max_items_(max_items),
        unknown_ns_(h.last_item_ns > 0 ? h.last_item_ns : target_ns),
        unknown_cap_(std::min(std::max<std::uint32_t>(1, 2 * h.last_refill),
                              std::max<std::uint32_t>(1, unclaimed / (2 * std::max<std::uint32_t>(1, threads))))) {}

  // Whether the refill takes one more item; `known_ns` is its cost where known, negative where not. An item
  // admitted is counted (the first is always admitted while max_items allows).
  bool admit(double known_ns) {
    if (taken_ >= max_items_ || worth_ns_ >= target_ns_) return false;
    if (known_ns < 0) {
      if (unknown_ >= unknown_cap_) return false;
      ++unknown_;
      known_ns = unknown_ns_;
    }
    worth_ns_ += known_ns;
    ++taken_;
    return true;
  }

  std::uint32_t taken() const { return taken_; }
  double worth_ns() const { return worth_ns_; }

 private:
  double target_ns_;
  std::uint32_t max_items_;
  double unknown_ns_;
  std::uint32_t unknown_cap_;
  double worth_ns_ = 0;
  std::uint32_t taken_ = 0, unknown_ = 0;
};

}  // namespace frontsteal::mpi
