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

TEST_CASE("the predicted cost extrapolates each item's trend over two frames, the factor clamped to [1/2, 2]",
          "[distributed][cost_seeded_lists]") {
  const std::vector<float> before{1.0f, 2.0f, 4.0f, 1.0f, 0.0f, 3.0f};
  const std::vector<float> last{1.2f, 2.0f, 1.0f, 8.0f, 5.0f, 0.0f};
  const std::vector<float> predicted = mpi::predicted_costs(last, before);
  REQUIRE(predicted.size() == last.size());
  CHECK(predicted[0] == Approx(1.2 * 1.2));       // +20 % a frame: +20 % again
  CHECK(predicted[1] == Approx(2.0));             // steady
  CHECK(predicted[2] == Approx(0.5));             // / 4 clamped to / 2
  CHECK(predicted[3] == Approx(16.0));            // x 8 clamped to x 2
  CHECK(predicted[4] == Approx(5.0));             // no earlier time: the last one
  CHECK(predicted[5] == Approx(0.0));             // not run last frame: nothing known
  CHECK(mpi::predicted_costs(last, {}) == last);  // the first prediction: one frame of times
}

TEST_CASE("heavy-first lists hold the block's ids once each, in runs of at most 16, heaviest runs first",
          "[distributed][cost_seeded_lists]") {
  const mpi::SyntheticCost cascade(mpi::CostShape::kCascade, 20000, 1, 20);
  std::vector<float> costs;
  for (ItemId id = 0; id < 20000; ++id) costs.push_back(static_cast<float>(cascade.units(0, id)));
  const frontsteal::RangeList block{{1000, 1037}, {5000, 9000}};
  const frontsteal::RangeList ordered = mpi::heavy_first(block, costs);
  std::vector<int> seen(20000, 0);
  double previous = 1e300;
  for (const IdRange& r : ordered) {
    // A run never crosses one of the block's ranges, and runs start on the block's 16-id grid.
    const bool inside = (r.begin >= 1000 && r.end <= 1037) || (r.begin >= 5000 && r.end <= 9000);
    CHECK(inside);
    for (ItemId id = r.begin; id < r.end; ++id) ++seen[id];
    // Runs merged by append_merging are consecutive ids; their mean cost cannot exceed the previous run's.
    for (ItemId b = r.begin; b < r.end;) {
      const ItemId base = b < 1037 ? 1000 : 5000;
      const ItemId e = std::min<ItemId>(r.end, base + ((b - base) / 16 + 1) * 16);
      double sum = 0;
      for (ItemId id = b; id < e; ++id) sum += costs[id];
      const double per_item = sum / (e - b);
      CHECK(per_item <= previous + 1e-9);
      previous = per_item;
      b = e;
    }
  }
  for (ItemId id = 0; id < 20000; ++id) {
    const bool in_block = (id >= 1000 && id < 1037) || (id >= 5000 && id < 9000);
    REQUIRE(seen[id] == (in_block ? 1 : 0));
  }
  // The control: id order is not heavy-first on the cascade (the check above has something to catch).
  double first_run = 0, best_run = 0;
  for (ItemId id = 5000; id < 5016; ++id) first_run += costs[id];
  for (ItemId b = 5000; b < 9000; b += 16) {
    double sum = 0;
    for (ItemId id = b; id < b + 16; ++id) sum += costs[id];
    best_run = std::max(best_run, sum);
  }
  CHECK(best_run > 2 * first_run);
}
