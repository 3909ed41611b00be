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

namespace {

// A run of `rounds` rounds with the arms of paired_arms(): rma (reference x speed), the reference, its twin
// (reference x twin_factor) and the planted arm (reference x 1.10, planted at 10 %). The reference drifts round to
// round by up to 30 %, as this machine's speed does; each arm gets its own small noise.
fm::PairedRun synthetic_paired_run(int rounds, double speed, double twin_factor) {
  fm::Options o;
  o.schedulers = {"rma", "static-space"};
  fm::PairedRun run;
  run.arms = fm::paired_arms(o);
  REQUIRE(run.arms.size() == 4);
  run.reference = 1;
  run.rounds.resize(4);
  run.results.resize(4);
  const double frames = 4;
  for (std::size_t a = 0; a < 4; ++a) run.results[a].frame_s.assign(static_cast<std::size_t>(rounds * 4), 0.0);
  run.arms[3].planted_s = 0.10 * 0.025;  // 10 % of a 25 ms frame
  for (int r = 0; r < rounds; ++r) {
    const double drift = 1.0 + 0.3 * ((r * 37) % 11) / 10.0;
    const double jitter[4] = {1 + 0.004 * ((r * 7) % 5 - 2), 1 + 0.004 * ((r * 3) % 5 - 2),
                              1 + 0.004 * ((r * 11) % 5 - 2), 1 + 0.004 * ((r * 13) % 5 - 2)};
    const double ref = frames * 0.025 * drift;
    const double times[4] = {ref / speed * jitter[0], ref * jitter[1], ref * twin_factor * jitter[2],
                             (ref + frames * run.arms[3].planted_s) * jitter[3]};
    for (std::size_t a = 0; a < 4; ++a) run.rounds[a].add(static_cast<std::size_t>(r), times[a], 0.0, 0);
  }
  return run;
}

}  // namespace

TEST_CASE("paired rounds: a 1.5x scheduler is faster, the twin equivalent, the planted 10 % found", "[mpi_report]") {
  const fm::PairedRun run = synthetic_paired_run(12, 1.5, 1.0);
  fm::PairedReport rep{"static-space", 12, 4, 5.0, fm::compare_arms(run, 5.0), {}};
  rep.method = fm::check_method(rep.comparisons);
  REQUIRE(rep.comparisons.size() == 3);
  CHECK(rep.comparisons[0].result.decision == frontsteal::measure::Decision::kFaster);
  CHECK(1 / rep.comparisons[0].result.chosen().ratio() == Approx(1.5).epsilon(0.01));
  CHECK(rep.method.twin_equivalent);
  CHECK(rep.method.planted_found);
  CHECK(rep.method.passed());
  CHECK(rep.comparisons[2].planted_pct > 5.0);  // the planted size relative to the drifting reference's mean
  const std::string answer = fm::paired_answer(rep);
  CHECK_THAT(answer, Catch::Contains("rma: 1.50x the speed of static-space"));
  CHECK_THAT(answer, !Catch::Contains("METHOD CHECK FAILED"));
  CHECK(fm::paired_table(rep).rows() == 3);
}

// The negative control: a twin that is really 10 % slower (the method then cannot be trusted) is called
// different, and the answer says the check failed.
TEST_CASE("paired rounds: a twin that differs fails the method check, and the answer says so", "[mpi_report]") {
  const fm::PairedRun run = synthetic_paired_run(12, 1.5, 1.10);
  fm::PairedReport rep{"static-space", 12, 4, 5.0, fm::compare_arms(run, 5.0), {}};
  rep.method = fm::check_method(rep.comparisons);
  CHECK(rep.method.twin_false_alarm);
  CHECK_FALSE(rep.method.passed());
  CHECK_THAT(fm::paired_answer(rep), Catch::Contains("METHOD CHECK FAILED"));
}
