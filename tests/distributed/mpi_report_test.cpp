// mpi_report_test.cpp — frontsteal-mpi's report (distributed/mpi_report.hpp): the medians come with 95 %
// intervals that contain them, and the noise warning appears exactly when a scheduler's window was busy (the
// quiet run is its deterministic negative control).
#include <catch2/catch.hpp>

#include "distributed/mpi_report.hpp"

namespace fm = frontsteal::mpi;

namespace {

fm::SchedulerResult result(bool busy) {
  fm::SchedulerResult r;
  r.name = "rma";
  r.frame_s = {0.010, 0.011, 0.012, 0.010, 0.013, 0.011, 0.050};
  fm::RankStats s;
  s.steals = 3;
  s.steal_latency_median_us = 12;
  s.steal_latency_ci_low_us = 10;
  s.steal_latency_ci_high_us = 15;
  r.ranks = {s, s};
  r.noise.busy = busy;
  r.noise.reason = busy ? "other processes used 40 % of the machine" : "";
  return r;
}

}  // namespace

TEST_CASE("the frame-time median of the intervals table lies inside its 95 % interval", "[mpi_report]") {
  const frontsteal::report::Table t = fm::intervals_table({result(false)});
  REQUIRE(t.rows() == 2);
  const double median = t.at(0, 2).value.get<double>();
  const double low = t.at(0, 3).value.get<double>();
  const double high = t.at(0, 4).value.get<double>();
  CHECK(median == Approx(11.0));
  CHECK(low <= median);
  CHECK(median <= high);
  CHECK(t.at(1, 2).value.is_null());  // frame columns on the scheduler's first row only
}

TEST_CASE("the noise warning names the busy scheduler, and a quiet run has none", "[mpi_report]") {
  CHECK(fm::noise_warning({result(false)}).empty());
  const std::string w = fm::noise_warning({result(true)});
  CHECK_THAT(w, Catch::Matchers::StartsWith("WARNING: the machine was not quiet"));
  CHECK_THAT(w, Catch::Matchers::Contains("rma: other processes used 40 %"));
}
