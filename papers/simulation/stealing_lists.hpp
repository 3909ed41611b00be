// stealing_lists.hpp — the parts of the stealing protocol (core/stealing_protocol.hpp, paper §4.2) that every
// model of it shares: the first frame's lists, each worker's order of victims, the split of a steal, and the
// carry-over of lists from one frame to the next (§4.2.1).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::simulation {

// The first frame's lists: worker w holds the contiguous block [n·w/p, n·(w+1)/p), as core/frame_loop.hpp's
// block allocation.
inline std::vector<std::vector<ItemId>> contiguous_blocks(ItemId n, std::uint32_t p) {
  std::vector<std::vector<ItemId>> lists(p);
  for (std::uint32_t w = 0; w < p; ++w) {
    const auto lo = static_cast<ItemId>(std::uint64_t{n} * w / p);
    const auto hi = static_cast<ItemId>(std::uint64_t{n} * (w + 1) / p);
    for (ItemId id = lo; id < hi; ++id) lists[w].push_back(id);
  }
  return lists;
}

// Worker `self`'s victims: every other worker once, in an order drawn from `rng` (an idle worker visits them
// round after round in this order).
template <typename Worker, typename Rng>
std::vector<Worker> victim_order(Worker self, Worker p, Rng& rng) {
  std::vector<Worker> order;
  for (Worker v = 0; v < p; ++v) {
    if (v != self) order.push_back(v);
  }
  std::shuffle(order.begin(), order.end(), rng);
  return order;
}

// A thief that read Front f and End e of a victim takes [mid, e): the victim keeps the lower half (the
// protocol's items_left_to_victim), so the share is the part the owner reaches last.
template <typename Index>
Index steal_mid(Index front, Index end) {
  return static_cast<Index>(front + items_left_to_victim(static_cast<std::uint64_t>(end - front)));
}

// The next frame's lists (§4.2.1): each worker keeps what it ran, in id order; an item run twice (only under
// a planted defect) goes to the first worker that ran it.
inline std::vector<std::vector<ItemId>> lists_from_runs(const std::vector<std::vector<ItemId>>& ran, ItemId n) {
  std::vector<char> taken(n, 0);
  std::vector<std::vector<ItemId>> next(ran.size());
  for (std::size_t w = 0; w < ran.size(); ++w) {
    for (ItemId id : ran[w]) {
      if (!taken[id]) next[w].push_back(id);
      taken[id] = 1;
    }
    std::sort(next[w].begin(), next[w].end());
  }
  return next;
}

}  // namespace frontsteal::simulation
