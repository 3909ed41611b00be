// cost_seeded_lists.hpp — the next frame's lists from this frame's measured item costs (persistence-based load
// balancing: Lifflander, Krishnamoorthy & Kalé, "Work stealing and persistence-based load balancers for
// iterative overdecomposed applications", HPDC 2012): split the ids, in their spatial order, into one
// contiguous block per rank of equal measured cost. The blocks keep a rank's region of space together (what a
// renderer that keeps each region's data on one node needs) and start the frame balanced as far as the last
// frame predicts this one; stealing takes care of what changed.
#pragma once

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

}  // namespace frontsteal::mpi
