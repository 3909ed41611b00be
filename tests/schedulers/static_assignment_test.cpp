// Static assignments (schedulers/static_assignment.hpp): partitions, balance, and what the annealing optimizes.
#include <cmath>
#include <random>

#include <catch2/catch.hpp>

#include "schedulers/static_assignment.hpp"

namespace fs = frontsteal;
namespace sc = frontsteal::sched;

namespace {

// Items in a few tight clusters with very uneven costs: the case that defeats naive dealing.
sc::WorkloadHints clustered(fs::ItemId n, std::uint64_t seed) {
  sc::WorkloadHints h;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> jitter(0.0, 0.05);
  std::uniform_real_distribution<double> cost(1.0, 100.0);
  for (fs::ItemId i = 0; i < n; ++i) {
    const double cluster = static_cast<double>(i % 5);
    h.centres.push_back({cluster + jitter(rng), 2 * cluster + jitter(rng), jitter(rng)});
    h.costs.push_back(i % 17 == 0 ? 40 * cost(rng) : cost(rng));
  }
  return h;
}

}  // namespace

TEST_CASE("round robin and the Morton deal are partitions with equal counts", "[static]") {
  const auto h = clustered(1001, 1);
  for (fs::WorkerId p : {1u, 2u, 3u, 8u}) {
    for (const auto& a : {sc::round_robin_assignment(1001, p), sc::morton_deal_assignment(1001, p, h)}) {
      REQUIRE_NOTHROW(sc::require_partition(a, p, 1001));
      for (const auto& list : a) REQUIRE(list.size() >= 1001 / p);
    }
  }
  REQUIRE_THROWS_AS(sc::require_partition({{0, 1}, {1}}, 2, 2), std::invalid_argument);
  REQUIRE_THROWS_AS(sc::require_partition({{0}, {}}, 2, 2), std::invalid_argument);
}

TEST_CASE("annealing balances estimated cost and separates nearby primitives", "[static]") {
  const auto h = clustered(2000, 7);
  for (fs::WorkerId p : {2u, 4u}) {
    CAPTURE(p);
    sc::AnnealingReport r;
    const sc::Assignment a = sc::annealed_assignment(2000, p, h, {.seed = 3}, &r);
    REQUIRE_NOTHROW(sc::require_partition(a, p, 2000));
    INFO("imbalance " << r.initial_imbalance << " -> " << r.final_imbalance << ", edge cost " << r.initial_edge_cost
                      << " -> " << r.final_edge_cost << ", accepted " << r.accepted << "/" << r.proposals);
    REQUIRE(r.final_imbalance < 1.02);
    REQUIRE(r.final_imbalance <= r.initial_imbalance);
    REQUIRE(r.final_edge_cost < r.initial_edge_cost);
    REQUIRE(r.accepted > 0);
    // Deterministic by seed.
    REQUIRE(sc::annealed_assignment(2000, p, h, {.seed = 3}) == a);
  }
}

TEST_CASE("annealing without hints degrades to a balanced deal", "[static]") {
  const sc::Assignment a = sc::annealed_assignment(100, 4, {});
  REQUIRE_NOTHROW(sc::require_partition(a, 4, 100));
  REQUIRE(sc::estimated_imbalance(a, {}) == Approx(1.0));
}
