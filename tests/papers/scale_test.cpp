// The simulated loss account (papers/simulator.hpp's SimulatedAccount, papers/scale.hpp): its terms add up to
// frame x P for every model; worked out by hand on a two-worker static frame (wake-up, work, claim, checks,
// termination); a steal's search and steal time land in those terms; the account's constants are read back
// from a measured set as documented (per model claim, wake by worker, join, inflation by P, core speeds); off-CPU
// time is put back where the main job took it from.
#include <catch2/catch.hpp>

#include "tests/papers/hand_made_trace.hpp"
#include "papers/scale.hpp"
#include "papers/simulator.hpp"
#include "schedulers/static_assignment.hpp"

namespace fp = frontsteal::papers;
using frontsteal::ItemId;
using frontsteal::WorkerId;

namespace {

fp::Overheads account_overheads() {
  fp::Overheads o;
  for (fp::ModelCosts* m : {&o.static_list, &o.queue, &o.stealing, &o.chase_lev}) *m = {2, 0, 0};
  o.checks_ns = 1;
  o.wake_by_worker_ns = {10, 30};
  o.join_ns = 5;
  return o;
}

double sum(const fp::SimulatedAccount& a) {
  return a.work + a.claim + a.checks + a.wake + a.search + a.steal + a.termination;
}

}  // namespace

TEST_CASE("simulated account: a static frame worked out by hand", "[papers][account]") {
  const fp::CostTrace t = fp::testing::hand_made_trace({{100, 200, 300, 400}});
  const frontsteal::sched::Assignment lists{{0, 2}, {1, 3}};
  const fp::SimulationOptions so{.model = fp::Model::static_list, .workers = 2, .assignment = &lists};
  const fp::SimulatedRun run = fp::simulate(t, account_overheads(), so);
  // Worker 0: wakes at 10, items 100 + 300 with 3 ns each (claim 2, checks 1): ends at 416.
  // Worker 1: wakes at 30, items 200 + 400: ends at 636. The frame ends 5 ns later: 641.
  REQUIRE(run.frame_ns.size() == 1);
  CHECK(run.frame_ns[0] == Approx(641));
  const fp::SimulatedAccount& a = run.account;
  CHECK(a.available == Approx(2 * 641));
  CHECK(a.work == Approx(1000));
  CHECK(a.claim == Approx(8));
  CHECK(a.checks == Approx(4));
  CHECK(a.wake == Approx(40));
  CHECK(a.termination == Approx((641 - 416) + (641 - 636)));
  CHECK(sum(a) == Approx(a.available));
}

TEST_CASE("simulated account: every model's terms add up to frame x P", "[papers][account]") {
  std::vector<std::vector<double>> costs(3, std::vector<double>(64, 10));
  for (std::size_t i = 0; i < 8; ++i) costs[1][i] = 500;  // a costly corner: steals and lock waits
  const fp::CostTrace t = fp::testing::hand_made_trace(costs);
  fp::Overheads o = account_overheads();
  o.line_transfer_ns = 20;
  o.fence_ns = 5;
  o.idle_round_ns = 7;
  o.lock_uncontended_ns = 3;
  o.lock_handoff_ns = 9;
  const frontsteal::sched::Assignment rr = frontsteal::sched::round_robin_assignment(64, 4);
  for (fp::Model m : {fp::Model::static_list, fp::Model::queue, fp::Model::stealing, fp::Model::chase_lev}) {
    CAPTURE(static_cast<int>(m));
    const fp::SimulatedRun run = fp::simulate(t, o, {.model = m, .workers = 4, .assignment = &rr, .seed = 3});
    CHECK(sum(run.account) == Approx(run.account.available).epsilon(1e-9));
    CHECK(run.account.wake == Approx(3 * (10 + 30 + (30 + o.extra_worker_ns()) + (30 + 2 * o.extra_worker_ns()))));
    if (m == fp::Model::stealing || m == fp::Model::chase_lev) {
      CHECK(run.steals > 0);
      CHECK(run.account.steal > 0);
    }
  }
}

TEST_CASE("the account's constants come from the calibration set's measured rows", "[papers][account]") {
  fp::MeasuredSet set;
  set.name = "cal";
  set.limit_copy_time[2] = {0.9, 1.1};
  auto row = [](const char* scheduler, WorkerId p, double claim, std::vector<double> wake_ms, double inflation) {
    fp::MeasuredCell c;
    c.scheduler = scheduler;
    c.workers = p;
    fp::MeasuredAccount a;
    a.claim_per_item_ns = claim;
    a.checks_per_item_ns = 4;
    a.frames = 10;
    a.wake_ms = std::move(wake_ms);
    a.termination_ms = std::vector<double>(a.wake_ms.size(), 0.5);
    a.inflation = inflation;
    c.account = a;
    return c;
  };
  set.cells = {row("stealing/Fenced", 1, 20, {0.4}, 1.0), row("stealing/Fenced", 2, 30, {0.6, 4.0}, 1.1),
               row("queue-mutex", 2, 3, {0.6, 6.0}, 1.2)};
  const fp::AccountConstants c = fp::account_constants(set, fp::Overheads{});
  CHECK(c.overheads.stealing.item_ns == 30);  // the largest P's
  CHECK(c.overheads.queue.item_ns == 3);
  CHECK(c.overheads.checks_ns == 4);
  REQUIRE(c.overheads.wake_by_worker_ns.size() == 2);
  CHECK(c.overheads.wake_by_worker_ns[0] == Approx(60'000));   // median of 40, 60, 60 us
  CHECK(c.overheads.wake_by_worker_ns[1] == Approx(500'000));  // median of 400, 600 us
  CHECK(c.overheads.join_ns == Approx(50'000));
  CHECK(c.inflation_at(1) == Approx(1.0));
  CHECK(c.inflation_at(2) == Approx(1.15));
  CHECK(c.inflation_at(16) == Approx(1.15));  // beyond: the largest measured P's
  CHECK(c.core_speed.at(2) == std::vector<double>{0.9, 1.1});
  fp::MeasuredSet none;
  none.name = "no accounts";
  CHECK_THROWS(fp::account_constants(none, fp::Overheads{}));
}

TEST_CASE("off-CPU time is put back into the terms it was taken from", "[papers][account]") {
  fp::MeasuredAccount m;
  m.shares = {{"work", 0.54}, {"search", 0.09}, {"termination", 0.18}, {"wake", 0.10}, {"off_cpu", 0.09}};
  const std::map<std::string, double> s = fp::comparable_shares(m);
  CHECK(s.at("work") == Approx(0.60));
  CHECK(s.at("search") == Approx(0.10));
  CHECK(s.at("termination") == Approx(0.20));
  CHECK(s.at("wake") == Approx(0.10));
}

TEST_CASE("the largest-item bound: no schedule of whole items ends a frame before its costliest item", "[papers]") {
  const fp::CostTrace even = fp::testing::hand_made_trace({{10, 10, 10, 10}});
  CHECK(fp::critical_path_bound(even, 2) == Approx(1.0));
  CHECK(fp::critical_path_bound(even, 8) == Approx(0.5));  // 40 / 8 = 5 per worker, but an item takes 10
  const fp::CostTrace skewed = fp::testing::hand_made_trace({{30, 2, 2, 2}, {10, 10, 10, 10}});
  // P = 4: frame 0 ideal 9, bound 30; frame 1 ideal 10, bound 10: (9 + 10) / (30 + 10).
  CHECK(fp::critical_path_bound(skewed, 4) == Approx(19.0 / 40.0));
}
