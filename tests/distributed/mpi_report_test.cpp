// mpi_report_test.cpp — frontsteal-mpi's report (distributed/mpi_report.hpp): the medians come with 95 %
// intervals that contain them, and the noise warning appears exactly when a scheduler's window was busy (the
// quiet run is its deterministic negative control).
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "distributed/mpi_plots.hpp"
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

// --plots: the data holds what the run measured (frame times in ms, one busy/idle row per rank), the script
// and the PNGs exist (bootstrap installs gnuplot); a directory that cannot be created is an error naming it,
// not a silently missing plot (its negative control).
TEST_CASE("the run plots hold the frame and per-rank data, with their script and both PNGs", "[mpi_report]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("frontsteal-mpi-plots-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fm::SchedulerResult a = result(false);
  a.ranks[0].busy_s = 1.5;
  a.ranks[0].idle_s = 0.25;
  fm::SchedulerResult b = result(false);
  b.name = "static";
  fm::write_run_plots(dir.string(), "2 ranks, test", {a, b});
  std::ifstream frames(dir / "frontsteal-mpi-frames.dat");
  const std::string f((std::istreambuf_iterator<char>(frames)), std::istreambuf_iterator<char>());
  CHECK(f.find("\"rma\"\n0 10\n1 11\n") == 0);
  CHECK(f.find("\"static\"") != std::string::npos);
  std::ifstream ranks(dir / "frontsteal-mpi-ranks.dat");
  const std::string r((std::istreambuf_iterator<char>(ranks)), std::istreambuf_iterator<char>());
  CHECK(r.find("\"rma r0\" 1.5 0.25 0\n") != std::string::npos);  // 0.117 s of frames < busy + idle: 0
  CHECK(r.find("\"rma r1\" 0 0 0.117\n") != std::string::npos);   // the whole frame time is "the rest"
  CHECK(r.find("\"static r1\"") != std::string::npos);
  CHECK(fs::exists(dir / "frontsteal-mpi.gp"));
  CHECK(fs::file_size(dir / "frontsteal-mpi-frames.png") > 1000);
  CHECK(fs::file_size(dir / "frontsteal-mpi-ranks.png") > 1000);
  fs::remove_all(dir);

  const fs::path file = fs::temp_directory_path() / ("frontsteal-mpi-plots-file-" + std::to_string(::getpid()));
  std::ofstream(file) << "x";
  REQUIRE_THROWS_WITH(fm::write_run_plots((file / "sub").string(), "t", {a}),
                      Catch::Matchers::Contains((file / "sub").string()));
  fs::remove(file);
}
