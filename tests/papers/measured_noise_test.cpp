// Tests of papers/measured_noise.hpp: a measured comparison on a quiet machine keeps its verdict; the same
// comparison is marked unreliable when others took the machine during the measurement or during one of its two
// cells (the negative controls of each rule), and not because single serial passes spread.
#include <catch2/catch.hpp>

#include "papers/measured_noise.hpp"

namespace fp = frontsteal::papers;
namespace nz = frontsteal::noise;

namespace {

// A window of 1000 ticks in which our own process used `self` and the whole machine `busy`.
nz::Usage window(std::uint64_t busy, std::uint64_t self) {
  nz::Usage u;
  u.total_ticks = 1000;
  u.busy_ticks = busy;
  u.self_ticks = self;
  u.wall_s = 5;
  u.windows = 1;
  return u;
}

fp::MeasuredRun cell(const char* scheduler, std::vector<double> path_ms, nz::Usage usage) {
  fp::MeasuredRun r;
  r.scheduler = scheduler;
  r.workers = 2;
  r.path_ms = std::move(path_ms);
  for (std::size_t k = 0; k < r.path_ms.size(); ++k) r.rounds.add(k, r.path_ms[k], 0, 0);  // no probe: raw interval
  r.usage = usage;
  return r;
}

const nz::Usage kQuiet = window(500, 500), kBusy = window(900, 500);  // others: 0 %, 40 % of the machine
const std::vector<double> kSteadySerial = {100, 101, 100}, kDriftingSerial = {100, 130, 100};

}  // namespace

TEST_CASE("a quiet measurement keeps its verdict", "[papers][noise]") {
  const fp::MeasuredNoise noise({kQuiet, kSteadySerial, {}, {}, {}});
  CHECK(noise.warnings().empty());
  const auto j =
      noise.judge(cell("stealing/Fenced", {90, 91, 89}, kQuiet), cell("queue-mutex", {100, 100, 100}, kQuiet));
  CHECK(j.reliable());
  CHECK(j.c.decision == frontsteal::measure::Decision::kFaster);
  CHECK(j.text().find("unreliable") == std::string::npos);
  CHECK(j.json()["verdict"] == "faster");
  fp::VerdictTally tally;
  tally.add(j);
  CHECK(tally.warning().empty());
}

TEST_CASE("others on the machine during the measurement make every verdict unreliable", "[papers][noise]") {
  const fp::MeasuredNoise noise({kBusy, kSteadySerial, {}, {}, {}});
  REQUIRE(noise.warnings().size() == 1);
  const auto j =
      noise.judge(cell("stealing/Fenced", {90, 91, 89}, kQuiet), cell("queue-mutex", {100, 100, 100}, kQuiet));
  CHECK_FALSE(j.reliable());
  CHECK(j.text().find("unreliable (faster") != std::string::npos);
  CHECK(j.json()["verdict"] == "unreliable");
  CHECK(j.json()["verdict_if_reliable"] == "faster");
  fp::VerdictTally tally;
  tally.add(j);
  CHECK(tally.unreliable == 1);
  CHECK(tally.warning().find("WARNING: 1 of 1") != std::string::npos);
}

TEST_CASE("a busy cell makes its comparisons unreliable, and only those", "[papers][noise]") {
  const fp::MeasuredNoise noise({kQuiet, kSteadySerial, {}, {}, {}});
  const auto busy =
      noise.judge(cell("stealing/Fenced", {90, 91, 89}, kBusy), cell("queue-mutex", {100, 100, 100}, kQuiet));
  CHECK_FALSE(busy.reliable());
  CHECK(busy.unreliable_because.find("stealing/Fenced P=2") != std::string::npos);
  const auto quiet = noise.judge(cell("chase-lev", {90, 91, 89}, kQuiet), cell("queue-mutex", {100, 100, 100}, kQuiet));
  CHECK(quiet.reliable());
}

TEST_CASE("a drifting serial loop no longer makes a verdict unreliable: the paired rounds carry it",
          "[papers][noise]") {
  const fp::MeasuredNoise noise({kQuiet, kDriftingSerial, {}, {}, {}});
  CHECK(noise.warnings().empty());
  CHECK(noise.line().find("spread 30.0 %") != std::string::npos);
  CHECK(noise.judge(cell("a", {90, 91, 89}, kQuiet), cell("b", {100, 100, 100}, kQuiet)).reliable());
}

TEST_CASE("a drifting serial loop beside a drifting CPU probe: the line says the machine changed speed",
          "[papers][noise]") {
  std::vector<double> probe;
  for (double ms : kDriftingSerial) probe.push_back(2e4 * ms);  // the probe follows the passes
  const fp::MeasuredNoise noise({kQuiet, kDriftingSerial, probe, {}, {}});
  CHECK(noise.line().find("the CPU itself changed speed") != std::string::npos);
  CHECK(noise.json()["cpu_varied"] == true);
  const fp::MeasuredNoise steady({kQuiet, kDriftingSerial, std::vector<double>(kDriftingSerial.size(), 2e6), {}, {}});
  CHECK(steady.line().find("did not change") != std::string::npos);
  CHECK(steady.json()["cpu_varied"] == false);
}
