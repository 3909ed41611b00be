// cost_seeded_lists.hpp — the next frame's lists from this frame's measured item costs (persistence-based load
// balancing: Lifflander, Krishnamoorthy & Kalé, "Work stealing and persistence-based load balancers for
// iterative overdecomposed applications", HPDC 2012): split the ids, in their spatial order, into one
// contiguous block per rank of equal measured cost. The blocks keep a rank's region of space together (what a
// renderer that keeps each region's data on one node needs) and start the frame balanced as far as the
// prediction goes; stealing takes care of what it missed.
//
// THE PREDICTION. The last frame's cost alone misses a moving camera by up to +-40 % per rank on the cost
// cascade at 256 ranks (SIMULATED, docs/mpi.md); a region's cost changes by a similar factor from one frame to
// the next when the view moves smoothly, so the prediction extrapolates each item's trend over the last two
// frames, the factor clamped to [1/2, 2] (a measured time's noise must not double an item's price).
// THE ORDER. A rank runs its block heaviest runs first (runs of kHeavyFirstRun consecutive ids, by predicted cost
// per item), so that the frame ends on light items: a heavy item started late is the frame's tail, and a thief
// taking the back half of a list takes light, plentiful items that are quick to spread.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::mpi {

// Block b is [cut[b], cut[b+1]), cut[0] = 0, cut[ranks] = costs.size(): the boundary after the item where the
// prefix cost first reaches (b / ranks) of the total. Every id is in exactly one block (blocks may be empty:
// one item can outweigh a rank's share). Costs must be >= 0; all zero gives equal counts.
inline std::vector<RangeList> cost_balanced_blocks(const std::vector<float>& costs, WorkerId ranks) {
  const auto n = static_cast<ItemId>(costs.size());
  double total = 0;
  for (float c : costs) total += c;
  if (total <= 0) return block_allocation(n, ranks);
  std::vector<RangeList> blocks(ranks);
  double prefix = 0;
  ItemId begin = 0, id = 0;
  for (WorkerId b = 0; b < ranks; ++b) {
    const double target = total * static_cast<double>(b + 1) / static_cast<double>(ranks);
    while (id < n && (b + 1 == ranks || prefix + costs[id] / 2 < target)) prefix += costs[id++];
    if (id > begin) blocks[b].push_back({begin, id});
    begin = id;
  }
  return blocks;
}

// Each item's predicted cost: last x (last / before), the factor clamped to [1/2, 2]; `last` alone where an item
// has no earlier time (before empty, or 0).
inline std::vector<float> predicted_costs(const std::vector<float>& last, const std::vector<float>& before) {
  std::vector<float> out(last);
  if (before.size() != last.size()) return out;
  for (std::size_t i = 0; i < last.size(); ++i) {
    if (last[i] > 0 && before[i] > 0) out[i] = last[i] * std::clamp(last[i] / before[i], 0.5f, 2.0f);
  }
  return out;
}

inline constexpr ItemId kHeavyFirstRun = 16;

// `block`'s ids as runs of at most kHeavyFirstRun consecutive ids (never crossing a range), ordered by decreasing
// mean cost per item (ties: id order). The same ids, each once.
inline RangeList heavy_first(const RangeList& block, const std::vector<float>& costs) {
  struct Run {
    IdRange ids;
    double per_item;
  };
  std::vector<Run> runs;
  for (const IdRange& r : block) {
    for (ItemId b = r.begin; b < r.end; b += kHeavyFirstRun) {
      const ItemId e = std::min<ItemId>(r.end, b + kHeavyFirstRun);
      double sum = 0;
      for (ItemId id = b; id < e; ++id) sum += id < costs.size() ? costs[id] : 0.0f;
      runs.push_back({{b, e}, sum / static_cast<double>(e - b)});
    }
  }
  std::stable_sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) { return a.per_item > b.per_item; });
  RangeList out;
  for (const Run& run : runs) append_merging(out, run.ids);
  return out;
}

}  // namespace frontsteal::mpi
