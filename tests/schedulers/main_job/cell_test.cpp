// main_job_cell_test.cpp — the main job's per-frame accounting (schedulers/main_job/cell.hpp), shared by the
// in-process and the child path: a clean frame adds its totals and fails nothing; each of the three audits
// (exactly once, the tessellation's own audit, the triangle count) is caught on its own, and the first
// problem is kept with its frame.
#include "schedulers/main_job/cell.hpp"

#include <catch2/catch.hpp>

namespace mj = frontsteal::main_job;
using frontsteal::ExecutionAudit;
using frontsteal::FrameStats;

namespace {

ExecutionAudit audit_of(std::uint64_t items, std::uint64_t lost = 0) {
  ExecutionAudit a;
  a.items = items;
  a.lost = lost;
  return a;
}

FrameStats two_workers(std::int64_t busy0, std::int64_t busy1) {
  FrameStats st;
  st.wall_ns = 4'000'000;
  st.workers.resize(2);
  st.workers[0].busy_ns = busy0;
  st.workers[0].items_processed = 3;
  st.workers[1].busy_ns = busy1;
  st.workers[1].items_processed = 5;
  return st;
}

}  // namespace

TEST_CASE("a clean frame adds its totals and fails no audit", "[main-job]") {
  mj::Cell c;
  const FrameStats st = two_workers(3'000'000, 1'000'000);
  const ExecutionAudit ok = audit_of(8);
  const double ms = mj::account_frame(c, 0, {st, ok, 120, 0, ""}, 120);
  CHECK(ms == 4.0);
  CHECK(c.frames_run == 1);
  CHECK(c.totals.items_processed == 8);
  REQUIRE(c.per_worker.size() == 2);
  CHECK(c.per_worker[1].items_processed == 5);
  CHECK(c.available == 8'000'000.0);
  CHECK(c.busy_over_available == 4'000'000.0);
  CHECK(c.imbalance_max == 1.5);
  CHECK_FALSE(c.failed());
  CHECK(c.first_problem.empty());
}

TEST_CASE("each audit is caught, and the first problem is kept with its frame", "[main-job][negative-control]") {
  const FrameStats st = two_workers(1, 1);
  const ExecutionAudit ok = audit_of(8);
  SECTION("an item lost") {
    mj::Cell c;
    const ExecutionAudit lost = audit_of(8, 1);
    mj::account_frame(c, 3, {st, lost, 120, 0, ""}, 120);
    CHECK(c.audit_failures == 1);
    CHECK(c.failed());
    CHECK(c.first_problem.rfind("frame 3: ", 0) == 0);
  }
  SECTION("surfaces failing the tessellation audit, named where known") {
    mj::Cell c;
    mj::account_frame(c, 2, {st, ok, 120, 4, "leaf_7"}, 120);
    CHECK(c.tessellation_inconsistencies == 4);
    CHECK(c.first_problem == "frame 2: 4 surfaces fail the tessellation audit (first: leaf_7)");
    mj::Cell child;
    mj::account_frame(child, 2, {st, ok, 120, 4, ""}, 120);
    CHECK(child.first_problem == "frame 2: 4 surfaces fail the tessellation audit");
  }
  SECTION("a triangle count other than the serial loop's; only the first problem is kept") {
    mj::Cell c;
    mj::account_frame(c, 1, {st, ok, 119, 0, ""}, 120);
    mj::account_frame(c, 2, {st, ok, 118, 0, ""}, 120);
    CHECK(c.triangle_mismatches == 2);
    CHECK(c.first_problem == "frame 1: 119 triangles, serial loop made 120");
  }
}
