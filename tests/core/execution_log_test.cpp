// The exactly-once audit from per-worker logs (core/execution_log.hpp): a clean frame passes; an item run by no
// worker is lost, one run twice (by one worker or by two) is duplicated; a worker that logs more ids than there
// are items is reported, not written past its log; the logs start empty after each audit.
#include "core/execution_log.hpp"

#include <catch2/catch.hpp>

namespace fs = frontsteal;
using fs::ItemId;

TEST_CASE("a frame in which every item ran once passes, and the log starts afresh", "[core][audit]") {
  fs::ExecutionLog log(10, 3);
  for (ItemId i = 0; i < 10; ++i) log.record(i, i % 3);
  const fs::ExecutionAudit a = log.audit_and_reset();
  CHECK(a.items == 10);
  CHECK(a.exactly_once());
  const fs::ExecutionAudit empty = log.audit_and_reset();
  CHECK(empty.lost == 10);  // nothing logged since: every item lost
}

TEST_CASE("lost and duplicated items are found, with examples", "[core][audit][negative-control]") {
  fs::ExecutionLog log(8, 2);
  for (ItemId i = 0; i < 8; ++i) {
    if (i != 3) log.record(i, 0);  // item 3 lost
  }
  log.record(5, 1);  // item 5 twice, on two workers
  log.record(6, 0);  // item 6 twice, on one worker
  const fs::ExecutionAudit a = log.audit_and_reset();
  CHECK(a.lost == 1);
  CHECK(a.first_lost == std::vector<ItemId>{3});
  CHECK(a.duplicated == 2);
  CHECK(a.extra_runs == 2);
  CHECK(a.first_duplicated == std::vector<ItemId>{5, 6});
  CHECK_FALSE(a.exactly_once());
}

TEST_CASE("a worker that logs more runs than there are items is reported as duplicated runs", "[core][audit]") {
  fs::ExecutionLog log(4, 1);
  for (int k = 0; k < 6; ++k) log.record(0, 0);  // 6 runs of item 0; the log holds 4 ids
  const fs::ExecutionAudit a = log.audit_and_reset();
  CHECK(a.duplicated >= 1);
  CHECK(a.extra_runs == 5);  // 3 counted from the log (4 runs of item 0), 2 beyond its end
  CHECK(a.lost == 3);        // items 1-3
}
