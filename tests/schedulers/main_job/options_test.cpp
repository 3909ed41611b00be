// options_test.cpp — frontsteal's command line (schedulers/main_job/options.hpp) turned into Options: the
// defaults a bare run measures with, each measurement flag landing in its field, what --calibrate adds, the
// interference set-up deciding the pinning, and the analysis settings every comparison is made with; and the
// segments and progress steps of a run (schedulers/main_job/run.hpp). Bad flags exit 2 (ctest
// frontsteal.usage_errors), so only accepted command lines are parsed here.
#include "schedulers/main_job/options.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "measure/machine_info.hpp"
#include "schedulers/main_job/run.hpp"

namespace mj = frontsteal::main_job;
namespace ms = frontsteal::measure;

namespace {

mj::Options parse(std::vector<std::string> args) {
  args.insert(args.begin(), "frontsteal");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return mj::parse_options(static_cast<int>(argv.size()), argv.data());
}

bool has(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

}  // namespace

TEST_CASE(
    "a bare run: every exactly-once scheduler at P = 1 .. cores and 2 x cores, rounds and instances as documented",
    "[main-job][options]") {
  const mj::Options o = parse({});
  const unsigned cores = frontsteal::hardware_cores();
  std::vector<frontsteal::WorkerId> want;
  for (unsigned p = 1; p <= cores; ++p) want.push_back(p);
  want.push_back(2 * cores);
  CHECK(o.threads == want);
  CHECK(has(o.schedulers, "queue-mutex"));
  CHECK(has(o.schedulers, "stealing/Fenced"));
  CHECK(o.repeats == 0);  // auto
  CHECK(o.round_frames == 1);
  CHECK(o.instance_frames == 6);
  CHECK(o.margin == Approx(0.02));
  CHECK(o.adjust);
  CHECK(o.estimator == ms::Estimator::kHuber);
  CHECK(o.order == ms::OrderKind::kRandom);
  CHECK(o.pin);
  CHECK_FALSE(o.interference);
  CHECK_FALSE(o.calibrate);
}

TEST_CASE("the measurement flags land in their fields, and the analysis settings follow them", "[main-job][options]") {
  const mj::Options o = parse({"--threads",
                               "2,3",
                               "--schedulers",
                               "queue-mutex,stealing/Minimal",
                               "--repeats",
                               "7",
                               "--round-frames",
                               "4",
                               "--instance-frames",
                               "0",
                               "--margin",
                               "5",
                               "--no-adjust",
                               "--estimator",
                               "mean",
                               "--order",
                               "counterbalanced",
                               "--frames",
                               "12",
                               "--no-pin"});
  CHECK(o.threads == std::vector<frontsteal::WorkerId>{2, 3});
  CHECK(o.schedulers == std::vector<std::string>{"queue-mutex", "stealing/Minimal"});
  CHECK(o.repeats == 7);
  CHECK(o.round_frames == 4);
  CHECK(o.instance_frames == 0);
  CHECK(o.frames == 12);
  CHECK_FALSE(o.pin);
  CHECK(o.order == ms::OrderKind::kCounterbalanced);
  const ms::Settings s = mj::analysis_settings(o);
  CHECK(s.margin == Approx(0.05));
  CHECK_FALSE(s.adjust_for_probe);
  CHECK(s.estimator == ms::Estimator::kMean);
  CHECK(s.confidence == Approx(0.95));
  // 12 frames in rounds of 4: 3 segments; a pass is one round per segment and P.
  CHECK(mj::segments(o) == 3);
  CHECK(mj::distinct_p(o) == 2);
  CHECK(mj::progress_steps(o) == 1 + 7 * 3);
}

TEST_CASE("the calibration flag adds its base scheduler and P = 1 and P = cores", "[main-job][options]") {
  const mj::Options o = parse({"--threads", "3", "--schedulers", "stealing/Fenced", "--calibrate"});
  const unsigned cores = frontsteal::hardware_cores();
  CHECK(o.calibrate);
  CHECK(has(o.schedulers, "queue-mutex"));  // the default base, added
  CHECK(std::find(o.threads.begin(), o.threads.end(), 1u) != o.threads.end());
  CHECK(std::find(o.threads.begin(), o.threads.end(), cores) != o.threads.end());
  CHECK(std::is_sorted(o.threads.begin(), o.threads.end()));
}

TEST_CASE("the interference set-up decides the pinning: pinned pins, unpinned leaves every thread to the OS",
          "[main-job][options]") {
  const mj::Options pinned = parse({"--interference", "40,pinned", "--no-pin"});
  REQUIRE(pinned.interference);
  CHECK(pinned.interference->pinned);
  CHECK(pinned.interference->duty == Approx(0.4));
  CHECK(pinned.pin);  // the set-up wins over --no-pin
  const mj::Options unpinned = parse({"--interference", "50"});
  REQUIRE(unpinned.interference);
  CHECK_FALSE(unpinned.interference->pinned);
  CHECK_FALSE(unpinned.pin);
}
