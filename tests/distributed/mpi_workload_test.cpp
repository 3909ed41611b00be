// distributed/mpi_workload.hpp and synthetic_cost.hpp: the workload every rank builds identically. The serial
// reference (what the audit compares every scheduler's triangle count with) is checked against the items run
// one by one here, and the synthetic cost shape against its definition: a fifth of the ids heavy, moving.
#include <catch2/catch.hpp>

#include <cstdint>
#include <set>

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

TEST_CASE("the synthetic workload's serial count is the sum of its items", "[distributed][workload]") {
  mpi::Options o;
  o.scene = "synthetic:300";
  o.work_ns = 0;
  mpi::Workload wl;
  mpi::build_workload(o, 0, wl);
  CHECK(wl.kind == "synthetic");
  REQUIRE(wl.n == 300);
  check_serial_is_sum_of_items(wl, 3);
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
