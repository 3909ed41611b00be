// Tests of papers/validation.hpp: the error arithmetic on known numbers, reading a main-job result, the
// interference slowdown and one prediction worked out by hand.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "papers/validation.hpp"

namespace fp = frontsteal::papers;

TEST_CASE("error: signed percent of the measured value - a non-positive measurement is refused") {
  CHECK(fp::error_pct(110, 100) == Approx(10));
  CHECK(fp::error_pct(90, 100) == Approx(-10));
  CHECK(fp::error_pct(100, 100) == Approx(0));
  CHECK_THROWS_AS(fp::error_pct(1, 0), std::invalid_argument);
  CHECK_THROWS_AS(fp::error_pct(1, -5), std::invalid_argument);
}

TEST_CASE("summary: median and worst of the absolute errors, the mean of the signed ones, the goal") {
  const fp::ErrorSummary s = fp::summarize_errors({1, -3, 12, -2, 4});
  CHECK(s.cells == 5);
  CHECK(s.median_abs_pct == Approx(3));
  CHECK(s.worst_abs_pct == Approx(12));
  CHECK(s.worst_index == 2);
  CHECK(s.mean_signed_pct == Approx(2.4));
  CHECK_FALSE(fp::meets_goal(s));  // worst 12 > 10
  CHECK(fp::meets_goal(fp::summarize_errors({1, -3, 2})));
  CHECK_FALSE(fp::meets_goal(fp::summarize_errors({6, -6, 1})));  // median 6 > 5
  // Negative control: the median of the signed errors (-6) is not what is reported (6).
  const fp::ErrorSummary n = fp::summarize_errors({-6, -6, 1});
  CHECK(n.median_abs_pct == Approx(6));
  CHECK(n.worst_abs_pct == Approx(6));
  CHECK(n.worst_index == 0);  // the first of equal worst errors
  CHECK_THROWS_AS(fp::summarize_errors({}), std::invalid_argument);
}

TEST_CASE("a main-job result is read - a missing key is refused with its name") {
  const auto file = std::filesystem::temp_directory_path() / "frontsteal-validation-test.json";
  {
    std::ofstream out(file);
    out << R"({"path": "walkthrough", "scene": "plant:200", "machine": "m1", "interference": {"on": true,
              "co_runner_core_share_measured": 0.25}, "serial": {"path_ms": 800},
              "results": [{"scheduler": "queue-mutex", "workers": 2, "path_ms": 500, "path_spread_pct": 7.5},
                          {"scheduler": "tbb-affinity", "workers": 1, "path_ms": 900, "path_spread_pct": 1}]})";
  }
  const fp::MeasuredSet s = fp::read_measured_set(file, "walkthrough-pinned");
  CHECK(s.name == "walkthrough-pinned");
  CHECK(s.path == "walkthrough");
  CHECK(s.machine == "m1");
  CHECK(s.interference);
  CHECK(s.co_runner_share == Approx(0.25));
  CHECK(s.serial_ms == Approx(800));
  REQUIRE(s.cells.size() == 2);
  CHECK(s.cells[0].scheduler == "queue-mutex");
  CHECK(s.cells[0].workers == 2);
  CHECK(s.cells[0].path_ms == Approx(500));
  const std::vector<double> slow = fp::slowdown_of(s, 2);
  REQUIRE(slow.size() == 2);
  CHECK(slow[0] == Approx(4.0 / 3.0));
  CHECK(slow[1] == Approx(1));
  CHECK(fp::model_of("queue-mutex") == fp::Model::queue);
  CHECK_FALSE(fp::model_of("tbb-affinity").has_value());
  {
    std::ofstream out(file);
    out << R"({"path": "walkthrough", "scene": "plant:200", "machine": "m1", "interference": {"on": false},
              "results": []})";
  }
  try {
    fp::read_measured_set(file, "x");
    FAIL("a result without 'serial' was accepted");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("'serial'") != std::string::npos);
  }
  std::filesystem::remove(file);
}

TEST_CASE("prediction: the trace scaled, the scheduler's model, the slowdown - the old model drops the new terms") {
  fp::CostTrace t;
  t.scene = "hand-made";
  for (int i = 0; i < 4; ++i) {
    t.centres.push_back({static_cast<double>(i), 0, 0});
    t.estimates.push_back(1);
  }
  t.cost_ns = {{1e6, 1e6, 1e6, 1e6}};  // 1 ms each
  fp::Overheads o;
  for (fp::ModelCosts* m : {&o.static_list, &o.queue, &o.stealing, &o.chase_lev}) *m = {0, 0, 0};
  // Round robin, P = 2, scale 2: each worker 2 items of 2 ms; worker 0 at 1.5x: 6 ms.
  CHECK(fp::predict_path_ms(t, 2.0, o, "round-robin", 2, {1.5, 1.0}, 1) == Approx(6));
  CHECK(fp::predict_path_ms(t, 2.0, o, "round-robin", 2, {}, 1) == Approx(4));
  CHECK_THROWS_AS(fp::predict_path_ms(t, 1.0, o, "tbb-affinity", 2, {}, 1), std::invalid_argument);
  o.affinity_penalty = 0.3;
  o.lock_wake_ns = 5000;
  o.wake_skew_ns = 70;
  const fp::Overheads b = fp::without_new_terms(o);
  CHECK(b.affinity_penalty == 0);
  CHECK(b.lock_wake_ns == 0);
  CHECK(b.wake_skew_ns == 0);
}

TEST_CASE("interval error: 0 inside the measured interval, else against the nearer bound") {
  const fp::MeasuredRatio m{1.0, 0.9, 1.2, true};
  CHECK(fp::interval_error_pct(1.0, m) == 0);
  CHECK(fp::interval_error_pct(0.9, m) == 0);  // the bounds are inside
  CHECK(fp::interval_error_pct(1.2, m) == 0);
  CHECK(fp::interval_error_pct(1.32, m) == Approx(10.0));   // 10 % above the upper bound
  CHECK(fp::interval_error_pct(0.81, m) == Approx(-10.0));  // 10 % below the lower bound
}

TEST_CASE("the simulator models four registry schedulers and no others") {
  CHECK(fp::model_of("round-robin") == fp::Model::static_list);
  CHECK(fp::model_of("queue-mutex") == fp::Model::queue);
  CHECK(fp::model_of("stealing/Fenced") == fp::Model::stealing);
  CHECK(fp::model_of("chase-lev") == fp::Model::chase_lev);
  CHECK_FALSE(fp::model_of("tbb-affinity").has_value());
  CHECK_FALSE(fp::model_of("stealing/Paper").has_value());  // another policy is another scheduler
  CHECK_FALSE(fp::model_of("").has_value());
}

TEST_CASE("the baseline model drops exactly the terms added for validation") {
  fp::Overheads o;
  o.affinity_penalty = 0.3;
  o.lock_wake_ns = 5000;
  o.wake_skew_ns = 15000;
  o.line_transfer_ns = 123;
  const fp::Overheads base = fp::without_new_terms(o);
  CHECK(base.affinity_penalty == 0);
  CHECK(base.lock_wake_ns == 0);
  CHECK(base.wake_skew_ns == 0);
  CHECK(base.line_transfer_ns == 123);  // the calibrated costs stay
}
