// distributed/cost_seeded_lists.hpp: the next frame's lists are a partition of the ids into contiguous blocks in
// rank order, each within one item of an equal share of the measured cost (checked against the costs summed
// here, block by block).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "distributed/cost_seeded_lists.hpp"
#include "distributed/synthetic_cost.hpp"

namespace mpi = frontsteal::mpi;
using frontsteal::IdRange;
using frontsteal::ItemId;
using frontsteal::WorkerId;

namespace {

void check_balanced_partition(const std::vector<float>& costs, WorkerId ranks) {
  const auto blocks = mpi::cost_balanced_blocks(costs, ranks);
  REQUIRE(blocks.size() == ranks);
  double total = 0, heaviest = 0;
  for (float c : costs) total += c, heaviest = std::max<double>(heaviest, c);
  ItemId next = 0;
  for (WorkerId b = 0; b < ranks; ++b) {
    INFO("block " << b);
    REQUIRE(blocks[b].size() <= 1);  // one contiguous range (or none)
    double cost = 0;
    for (const IdRange& r : blocks[b]) {
      CHECK(r.begin == next);  // contiguous, in rank order, nothing skipped
      for (ItemId id = r.begin; id < r.end; ++id) cost += costs[id];
      next = r.end;
    }
    CHECK(cost <= total / ranks + heaviest + 1e-6 * total);
  }
  CHECK(next == costs.size());  // every id in exactly one block
}

}  // namespace

TEST_CASE("cost-seeded lists are contiguous blocks of equal measured cost", "[distributed][cost_seeded_lists]") {
  check_balanced_partition(std::vector<float>(1000, 1.0f), 4);  // equal costs: equal counts
  std::vector<float> ramp;
  for (int i = 0; i < 5000; ++i) ramp.push_back(static_cast<float>(i % 97));
  check_balanced_partition(ramp, 7);
  const mpi::SyntheticCost cascade(mpi::CostShape::kCascade, 20000, 1, 20);
  std::vector<float> concentrated;
  for (ItemId id = 0; id < 20000; ++id) concentrated.push_back(static_cast<float>(cascade.units(0, id)));
  for (WorkerId ranks : {2u, 4u, 16u, 256u}) check_balanced_partition(concentrated, ranks);
}

TEST_CASE(
    "cost-seeded lists with no measured cost fall back to equal counts, and one heavy item may leave a block empty",
    "[distributed][cost_seeded_lists]") {
  const auto equal = mpi::cost_balanced_blocks(std::vector<float>(10, 0.0f), 3);
  CHECK(equal == frontsteal::block_allocation(10, 3));
  std::vector<float> one_heavy(10, 0.0f);
  one_heavy[0] = 100;
  check_balanced_partition(one_heavy, 4);
}
