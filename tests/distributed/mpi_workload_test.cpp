// distributed/mpi_workload.hpp and synthetic_cost.hpp: the workload every rank builds identically. The serial
// reference (what the audit compares every scheduler's triangle count with) is checked against the items run
// one by one here, and the synthetic cost shapes against their definitions: a fifth of the ids heavy, moving;
// the cascade's mass conserved split by split, and the need it exists for (static by space far from ideal).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "distributed/mpi_workload.hpp"
#include "distributed/synthetic_cost.hpp"

namespace mpi = frontsteal::mpi;
using frontsteal::ItemId;

TEST_CASE("a fifth of the synthetic ids are heavy, and the window moves every frame", "[distributed][workload]") {
  for (ItemId n : {ItemId{100}, ItemId{20000}, ItemId{37}}) {
    std::set<ItemId> previous;
    for (int f = 0; f < 4; ++f) {
      std::set<ItemId> heavy;
      for (ItemId id = 0; id < n; ++id) {
        if (mpi::synthetic_heavy(f, id, n)) heavy.insert(id);
      }
      INFO("n " << n << ", frame " << f);
      CHECK(heavy.size() == n - (4 * std::uint64_t{n} + 4) / 5);  // ids whose shifted value is ≥ 4n/5
      if (f > 0) CHECK(heavy != previous);                        // last frame's allocation is never quite right
      previous = heavy;
    }
  }
}

namespace {

// Work / (ranks x the busiest rank's work) when rank r runs the ids `owner(id) == r`.
template <class Owner>
double static_efficiency(const mpi::SyntheticCost& c, int frame, int ranks, Owner owner) {
  std::vector<double> load(static_cast<std::size_t>(ranks), 0.0);
  double total = 0;
  for (ItemId id = 0; id < c.items(); ++id) {
    load[static_cast<std::size_t>(owner(id))] += c.units(frame, id);
    total += c.units(frame, id);
  }
  return total / (ranks * *std::max_element(load.begin(), load.end()));
}

}  // namespace

TEST_CASE("the cost cascade conserves its mass split by split and moves from frame to frame",
          "[distributed][workload]") {
  const ItemId n = 1 << 14;
  const mpi::SyntheticCost c(mpi::CostShape::kCascade, n, 3, 20);
  const mpi::SyntheticCost again(mpi::CostShape::kCascade, n, 3, 20);
  for (int f = 0; f < 3; ++f) {
    INFO("frame " << f);
    double total = 0;
    for (ItemId id = 0; id < n; ++id) {
      CHECK(c.units(f, id) > 0);
      CHECK(c.units(f, id) == again.units(f, id));  // every rank builds the same costs
      total += c.units(f, id);
    }
    CHECK(total == Approx(n).epsilon(1e-4));  // mean 1 per item
    // Every split of the top levels sends p of its mass to one half, p in [0.55, 0.9]; below, p in [0.475, 0.525].
    for (ItemId width = n; width >= 2; width /= 2) {
      const bool moving = width > (n >> mpi::SyntheticCost::kMovingLevels);
      for (ItemId lo = 0; lo < n; lo += width) {
        double left = 0, right = 0;
        for (ItemId id = lo; id < lo + width / 2; ++id) left += c.units(f, id);
        for (ItemId id = lo + width / 2; id < lo + width; ++id) right += c.units(f, id);
        const double p = std::max(left, right) / (left + right);
        if (moving) {
          CHECK(p >= 0.55 - 1e-4);
          CHECK(p <= 0.9 + 1e-4);
        } else {
          CHECK(p <= 0.525 + 1e-4);
        }
      }
    }
  }
  double same = 0;
  for (ItemId id = 0; id < n; ++id) same += c.units(0, id) == c.units(1, id) ? 1 : 0;
  CHECK(same < n / 2);  // the costs move: last frame's allocation is not this frame's
}

TEST_CASE("the cost cascade needs stealing: static by space is far from ideal at 4 and at 256 ranks",
          "[distributed][workload]") {
  const ItemId n = 200000;
  const mpi::SyntheticCost c(mpi::CostShape::kCascade, n, 2, 20);
  for (int f = 0; f < 2; ++f) {
    const auto blocks_of = [n](int ranks) {
      return [n, ranks](ItemId id) { return static_cast<int>(std::uint64_t{id} * ranks / n); };
    };
    const auto round_robin = [](int ranks) { return [ranks](ItemId id) { return static_cast<int>(id % ranks); }; };
    INFO("frame " << f);
    CHECK(static_efficiency(c, f, 4, blocks_of(4)) < 0.7);
    CHECK(static_efficiency(c, f, 256, blocks_of(256)) < 0.5);
    CHECK(static_efficiency(c, f, 4, round_robin(4)) > 0.9);  // many items per hot spot: round robin copes
    double heaviest = 0;
    for (ItemId id = 0; id < n; ++id) heaviest = std::max(heaviest, c.units(f, id));
    CHECK(heaviest < 0.25 * n / 256.0);  // no item near a rank's ideal share at 256: ideal is reachable
  }
}

namespace {

// Checks that frame f's serial reference is the sum of the items run one by one here.
void check_serial_is_sum_of_items(mpi::Workload& wl, int frames) {
  for (int f = 0; f < frames; ++f) {
    std::uint64_t sum = 0;
    for (ItemId id = 0; id < wl.n; ++id) sum += wl.run(f, id);
    INFO("frame " << f);
    CHECK(sum > 0);
    CHECK(wl.serial_triangles(f) == sum);
  }
}

}  // namespace

TEST_CASE("each synthetic shape's serial count is the sum of its items", "[distributed][workload]") {
  for (const char* shape : {"synthetic", "cascade"}) {
    INFO(shape);
    mpi::Options o;
    o.scene = std::string(shape) + ":300";
    o.work_ns = 0;
    mpi::Workload wl;
    mpi::build_workload(o, 0, wl);
    CHECK(wl.kind == shape);
    REQUIRE(wl.n == 300);
    REQUIRE(wl.cost.has_value());
    check_serial_is_sum_of_items(wl, 3);
  }
}

TEST_CASE("the tessellation workload's serial reference is its own items, frame by frame", "[distributed][workload]") {
  mpi::Options o;
  o.scene = "teacup";
  o.frames = 2;
  mpi::Workload wl;
  mpi::build_workload(o, 0, wl);
  CHECK(wl.kind == "tessellation");
  REQUIRE(wl.n == 26);  // the teacup's patches
  REQUIRE(wl.serial.size() == 2);
  check_serial_is_sum_of_items(wl, 2);
  mpi::Workload other_rank;  // ranks other than 0 skip the serial loop
  mpi::build_workload(o, 1, other_rank);
  CHECK(other_rank.serial.empty());
  CHECK(other_rank.n == wl.n);
}
