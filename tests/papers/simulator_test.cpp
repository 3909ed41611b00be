// Tests of papers/simulator.hpp, papers/cost_trace.hpp and papers/calibration.hpp: each model against costs
// worked out by hand, the stealing model's audit against its planted lost steal, and the file formats.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/papers/hand_made_trace.hpp"
#include "papers/calibration.hpp"
#include "papers/cost_trace.hpp"
#include "papers/simulator.hpp"
#include "schedulers/static_assignment.hpp"

namespace fp = frontsteal::papers;
using frontsteal::ItemId;

namespace {

// No scheduler costs at all: the models reduce to list scheduling of the item costs.
fp::Overheads free_overheads() {
  fp::Overheads o;
  for (fp::ModelCosts* m : {&o.static_list, &o.queue, &o.stealing, &o.chase_lev}) *m = {0, 0, 0};
  o.line_transfer_ns = o.lock_uncontended_ns = o.lock_handoff_ns = o.fence_ns = o.idle_round_ns = 0;
  return o;
}

}  // namespace

TEST_CASE("static model: the frame lasts as long as the most loaded list, plus the frame cost") {
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 20, 30, 40}, {1, 1, 1, 1}});
  fp::Overheads o = free_overheads();
  o.static_list = {.item_ns = 2, .frame_fixed_ns = 100, .second_worker_ns = 50};
  const frontsteal::sched::Assignment lists = {{0, 3}, {1, 2}};
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::static_list, .workers = 2, .assignment = &lists});
  REQUIRE(r.frame_ns.size() == 2);
  CHECK(r.frame_ns[0] == Approx(std::max(10 + 40 + 4, 20 + 30 + 4) + 150));
  CHECK(r.frame_ns[1] == Approx(1 + 2 + 1 + 2 + 150));
  CHECK(r.audit_failures == 0);
}

TEST_CASE("every model at P = 1 is the serial sum plus its per-item and per-frame costs") {
  const fp::CostTrace t = fp::testing::hand_made_trace({{5, 7, 11, 13, 17}});
  fp::Overheads o = free_overheads();
  o.queue = o.stealing = o.chase_lev = o.static_list = {.item_ns = 1, .frame_fixed_ns = 10, .second_worker_ns = 0};
  const auto lists = frontsteal::sched::round_robin_assignment(5, 1);
  for (fp::Model m : {fp::Model::static_list, fp::Model::queue, fp::Model::stealing, fp::Model::chase_lev}) {
    const fp::SimulatedRun r = fp::simulate(t, o, {.model = m, .workers = 1, .assignment = &lists});
    INFO("model " << static_cast<int>(m));
    CHECK(r.path_ns == Approx(53 + 5 + 10));
    CHECK(r.audit_failures == 0);
  }
}

TEST_CASE("stealing: an idle worker takes the second half of a busy worker's list, and lists carry over") {
  // Worker 0's block holds all the expensive items; worker 1's block is free.
  std::vector<double> costs(8, 0);
  for (int i = 0; i < 4; ++i) costs[i] = 100;
  const fp::CostTrace t = fp::testing::hand_made_trace({costs, costs});
  const fp::Overheads o = free_overheads();
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::stealing, .workers = 2});
  CHECK(r.audit_failures == 0);
  CHECK(r.steals >= 1);
  // Frame 0: worker 0 starts item 0 at t=0; worker 1 runs its four free items at once, then steals items 2..3
  // (the second half of 1..3, victim keeps 1): 200 ns. Frame 1 starts from those lists: balanced, 200 ns.
  CHECK(r.frame_ns[0] == Approx(200));
  CHECK(r.frame_ns[1] == Approx(200));
  CHECK(r.utilization_pct == Approx(100));
}

TEST_CASE("stealing: the audit catches a steal that never lowers the victim's End (negative control)") {
  std::vector<double> costs(64, 10);
  for (int i = 0; i < 32; ++i) costs[i] = 1000;
  const fp::CostTrace t = fp::testing::hand_made_trace({costs});
  const fp::Overheads o = free_overheads();
  const fp::SimulatedRun sound = fp::simulate(t, o, {.model = fp::Model::stealing, .workers = 4});
  const fp::SimulatedRun planted =
      fp::simulate(t, o, {.model = fp::Model::stealing, .workers = 4, .plant_lost_steal = true});
  CHECK(sound.audit_failures == 0);
  CHECK(planted.audit_failures == 1);
}

TEST_CASE("queue: a saturated lock serializes the claims") {
  // 1000 free items, grain N/(100P) = 5 at P = 2: 200 acquisitions; each waiting one costs the handoff.
  const fp::CostTrace t = fp::testing::hand_made_trace({std::vector<double>(1000, 0)});
  fp::Overheads o = free_overheads();
  o.lock_uncontended_ns = 10;
  o.lock_handoff_ns = 100;
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::queue, .workers = 2});
  CHECK(r.audit_failures == 0);
  CHECK(r.lock_waits > 0);
  CHECK(r.path_ns >= 200 * 10);
  CHECK(r.path_ns <= 200 * 100 + 100);
}

TEST_CASE("Chase-Lev and queue balance what round robin cannot") {
  std::vector<double> costs(400, 1);
  for (int i = 0; i < 100; ++i) costs[i * 4] = 400;  // every 4th item is expensive: round robin puts them on worker 0
  const fp::CostTrace t = fp::testing::hand_made_trace({costs});
  fp::Overheads o = free_overheads();
  const auto rr = frontsteal::sched::round_robin_assignment(400, 4);
  const double static_ns =
      fp::simulate(t, o, {.model = fp::Model::static_list, .workers = 4, .assignment = &rr}).path_ns;
  for (fp::Model m : {fp::Model::queue, fp::Model::stealing, fp::Model::chase_lev}) {
    const fp::SimulatedRun r = fp::simulate(t, o, {.model = m, .workers = 4});
    INFO("model " << static_cast<int>(m));
    CHECK(r.audit_failures == 0);
    CHECK(r.path_ns < 0.5 * static_ns);
  }
}

TEST_CASE("cost traces survive a round trip, and a truncated trace is refused with its line") {
  const auto dir = std::filesystem::temp_directory_path() / "frontsteal-trace-test";
  std::filesystem::create_directories(dir);
  fp::CostTrace t = fp::testing::hand_made_trace({{1, 2, 3}, {4, 5, 6}});
  t.machine = "test machine";
  fp::write_cost_trace(t, dir / "t.txt");
  const fp::CostTrace back = fp::read_cost_trace(dir / "t.txt");
  CHECK(back.cost_ns == t.cost_ns);
  CHECK(back.machine == "test machine");
  CHECK(back.frame_cost_ns(1) == Approx(15));
  {  // drop the last frame line
    std::ifstream in(dir / "t.txt");
    std::ofstream out(dir / "cut.txt");
    std::string line, previous;
    bool first = true;
    while (std::getline(in, line)) {
      if (!first) out << previous << '\n';
      previous = line;
      first = false;
    }
  }
  CHECK_THROWS_WITH(fp::read_cost_trace(dir / "cut.txt"), Catch::Contains("truncated"));
  {
    std::ofstream bad(dir / "bad.txt");
    bad << "frontsteal-cost-trace 1\nsurfaces 2\nframes 1\nsurface 0 0 0 0 1\nsurface 1 0 0 0 1\nframe 0 5 x\n";
  }
  CHECK_THROWS_WITH(fp::read_cost_trace(dir / "bad.txt"), Catch::Contains("bad.txt:6"));
  CHECK_THROWS_AS(fp::read_cost_trace(dir / "missing.txt"), fp::TraceError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("calibration files survive a round trip, and unknown keys are refused") {
  const auto dir = std::filesystem::temp_directory_path() / "frontsteal-calibration-test";
  std::filesystem::create_directories(dir);
  fp::Overheads o;
  o.stealing.item_ns = 7.5;
  o.line_transfer_ns = 55;
  o.assumed = false;
  fp::write_overheads(o, dir / "c.txt");
  const fp::Overheads back = fp::read_overheads(dir / "c.txt");
  CHECK(back.stealing.item_ns == Approx(7.5));
  CHECK(back.line_transfer_ns == Approx(55));
  CHECK_FALSE(back.assumed);
  {
    std::ofstream bad(dir / "bad.txt");
    bad << "frontsteal-calibration 1\nwarp_factor 9\n";
  }
  CHECK_THROWS_WITH(fp::read_overheads(dir / "bad.txt"), Catch::Contains("warp_factor"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("stealing and Chase-Lev terminate when single items are left to steal") {
  // Free items and more workers than items: idle workers must not pass one item back and forth forever.
  const fp::CostTrace t = fp::testing::hand_made_trace({{0, 0, 0}, {5, 0, 0}, {0, 0, 9}});
  fp::Overheads o = free_overheads();
  o.line_transfer_ns = 1;
  for (fp::Model m : {fp::Model::stealing, fp::Model::chase_lev}) {
    const fp::SimulatedRun r = fp::simulate(t, o, {.model = m, .workers = 4});
    INFO("model " << static_cast<int>(m));
    CHECK(r.audit_failures == 0);
    CHECK(r.frame_ns.size() == 3);
  }
}

// ---- the terms added for validation: cache affinity, worker slowdown, wake-up skew, lock wake ----

TEST_CASE("affinity: the penalty is charged exactly when an item changes worker, and ignoring it is caught") {
  // Queue, P = 2, grain 1, no scheduler costs. Frame 0 (all 10): worker 0 runs {0, 2}, worker 1 {1, 3}; no
  // previous frame, no penalty. Frame 1: item 0 costs 30, so worker 1 runs {1, 2, 3}: item 2 moved (0 → 1) and
  // costs 10 × 1.5 = 15. Worker 1: 10 + 15 + 10 = 35; worker 0: 30. Path: 20 + 35.
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 10, 10, 10}, {30, 10, 10, 10}});
  fp::Overheads o = free_overheads();
  o.affinity_penalty = 0.5;
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::queue, .workers = 2});
  CHECK(r.audit_failures == 0);
  CHECK(r.affinity_misses == 1);
  CHECK(r.affinity_penalty_ns == Approx(5));
  CHECK(r.path_ns == Approx(55));
  // Negative control: a model that ignores the penalty predicts 50, which the check above would reject.
  fp::SimulationOptions planted{.model = fp::Model::queue, .workers = 2};
  planted.plant_ignore_affinity = true;
  const fp::SimulatedRun p = fp::simulate(t, o, planted);
  CHECK(p.path_ns == Approx(50));
  CHECK(p.path_ns != Approx(r.path_ns));
}

TEST_CASE("affinity: lists that stay with their worker never pay - at P = 1 nothing ever moves") {
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 20, 30, 40}, {40, 30, 20, 10}, {5, 5, 5, 5}});
  fp::Overheads o = free_overheads();
  o.affinity_penalty = 1.0;
  const auto rr = frontsteal::sched::round_robin_assignment(4, 2);
  const fp::SimulatedRun s = fp::simulate(t, o, {.model = fp::Model::static_list, .workers = 2, .assignment = &rr});
  CHECK(s.affinity_misses == 0);
  CHECK(s.path_ns == Approx(60 + 60 + 10));  // round robin: {0, 2} and {1, 3}
  for (fp::Model m : {fp::Model::queue, fp::Model::stealing, fp::Model::chase_lev}) {
    const fp::SimulatedRun one = fp::simulate(t, o, {.model = m, .workers = 1});
    CHECK(one.affinity_misses == 0);
    CHECK(one.path_ns == Approx(100 + 100 + 20));
  }
}

TEST_CASE("interference: a slowed worker's items take longer - a slowdown per worker is required") {
  // Round robin at P = 2: worker 0 runs items 0 and 2 at half speed: 2 × (10 + 10) = 40; worker 1: 20.
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 10, 10, 10}});
  const auto rr = frontsteal::sched::round_robin_assignment(4, 2);
  fp::SimulationOptions so{.model = fp::Model::static_list, .workers = 2, .assignment = &rr};
  so.worker_slowdown = {2.0, 1.0};
  CHECK(fp::simulate(t, free_overheads(), so).path_ns == Approx(40));
  so.worker_slowdown = {1.0, 1.0};  // negative control: no slowdown, the frame is the balanced 20
  CHECK(fp::simulate(t, free_overheads(), so).path_ns == Approx(20));
  so.worker_slowdown = {2.0};
  CHECK_THROWS_AS(fp::simulate(t, free_overheads(), so), std::invalid_argument);
}

TEST_CASE("wake-up: worker w starts its frame w x wake_skew_ns late") {
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 10, 10, 10}});
  const auto rr = frontsteal::sched::round_robin_assignment(4, 2);
  fp::Overheads o = free_overheads();
  o.wake_skew_ns = 3;
  CHECK(fp::simulate(t, o, {.model = fp::Model::static_list, .workers = 2, .assignment = &rr}).path_ns == Approx(23));
  o.wake_skew_ns = 0;  // negative control: without the skew the frame is 20
  CHECK(fp::simulate(t, o, {.model = fp::Model::static_list, .workers = 2, .assignment = &rr}).path_ns == Approx(20));
}

TEST_CASE("queue: a waiter sleeps and gets the lock lock_wake_ns after the holder's release") {
  // Two items of 10, grain 1. Worker 0 takes the lock at 0 for 5 and runs item 0 until 15. Worker 1 asks at 0,
  // sleeps, is granted at 5 + 7 = 12, holds for the hand-off 4 and runs item 1 from 16 to 26.
  const fp::CostTrace t = fp::testing::hand_made_trace({{10, 10}});
  fp::Overheads o = free_overheads();
  o.lock_uncontended_ns = 5;
  o.lock_handoff_ns = 4;
  o.lock_wake_ns = 7;
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::queue, .workers = 2});
  CHECK(r.lock_waits == 1);
  CHECK(r.path_ns == Approx(26));
  o.lock_wake_ns = 0;  // negative control: an immediate hand-off gives 5 + 4 + 10 = 19
  CHECK(fp::simulate(t, o, {.model = fp::Model::queue, .workers = 2}).path_ns == Approx(19));
}

TEST_CASE("queue: a running worker takes the lock while a sleeper wakes up (no convoy)") {
  // Three items of 1, grain 1, uncontended hold 5, hand-off 4, wake-up 7. Worker 0: lock 0-5, item 0 to 6;
  // worker 1 asks at 0, sleeps, runs again at 5 + 7 = 12. Worker 0 asks at 6: the lock is free, it takes it
  // (6-11) and runs item 1 to 12; at 12 it asks first (ties go to the lower worker): 12-17, item 2 to 18;
  // worker 1 finds the queue empty. Path 18. A lock reserved for the sleeper (the convoy) gives 28: worker 1
  // holds it 12-16, worker 0 sleeps at 6 and gets it at 16 + 7 = 23.
  const fp::CostTrace t = fp::testing::hand_made_trace({{1, 1, 1}});
  fp::Overheads o = free_overheads();
  o.lock_uncontended_ns = 5;
  o.lock_handoff_ns = 4;
  o.lock_wake_ns = 7;
  const fp::SimulatedRun r = fp::simulate(t, o, {.model = fp::Model::queue, .workers = 2});
  CHECK(r.path_ns == Approx(18));
  CHECK(r.lock_waits == 1);
}

TEST_CASE("calibration files carry the new constants, and files without them read as the terms off") {
  const auto file = std::filesystem::temp_directory_path() / "frontsteal-calibration-terms-test.txt";
  fp::Overheads o;
  o.lock_wake_ns = 4321;
  o.wake_skew_ns = 12.5;
  o.affinity_penalty = 0.25;
  o.affinity_measured = true;
  fp::write_overheads(o, file);
  const fp::Overheads back = fp::read_overheads(file);
  CHECK(back.lock_wake_ns == Approx(4321));
  CHECK(back.wake_skew_ns == Approx(12.5));
  CHECK(back.affinity_penalty == Approx(0.25));
  CHECK(back.affinity_measured);
  {
    std::ofstream old(file);
    old << "frontsteal-calibration 1\nmachine m\nline_transfer_ns 80\n";
  }
  const fp::Overheads old = fp::read_overheads(file);
  CHECK(old.affinity_penalty == 0);
  CHECK_FALSE(old.affinity_measured);
  CHECK(old.lock_wake_ns == 0);
  CHECK(old.wake_skew_ns == 0);
  std::filesystem::remove(file);
}
