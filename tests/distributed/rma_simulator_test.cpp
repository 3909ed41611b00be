// rma_simulator_test.cpp — the distributed simulator's own audit (rma_simulator.hpp): every scheduler runs
// each item exactly once per frame, with and without the transport's target-progress delay, and the planted
// skip-reread defect is caught (deterministic: a fixed seed and a configuration where victims run many
// items between a thief's T1 and T3); stealing happens and pays under skew (control: thieves that plan an
// empty share).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
#include <utility>

#include "distributed/rma_simulator.hpp"
#include "distributed/simulator_validation.hpp"

namespace sim = frontsteal::mpi::sim;

namespace {

sim::Latencies shared_memory_like() {
  sim::Latencies l;
  l.source = "test";
  l.get = l.put = 130;
  l.cas = l.fetch_op = 210;
  l.ping_pong = 800;
  l.claim = 40;
  l.poll = 130;
  l.progress_call = 130;
  l.atomic_service = 80;
  return l;
}

sim::Workload small() {
  sim::Workload w;
  w.items = 4000;
  w.light_ns = 1000;
  w.skew = 20;
  w.frames = 4;
  return w;
}

}  // namespace

TEST_CASE("every simulated scheduler runs each item exactly once per frame", "[rma_simulator]") {
  for (const bool tcp : {false, true}) {
    sim::Latencies lat = shared_memory_like();
    lat.needs_target_progress = tcp;
    for (sim::Scheduler s : {sim::Scheduler::kRma, sim::Scheduler::kRequest, sim::Scheduler::kCentral,
                             sim::Scheduler::kStatic, sim::Scheduler::kStaticSpace}) {
      for (int ranks : {2, 16, 64}) {
        const sim::Result r = sim::simulate(s, ranks, small(), lat);
        INFO(sim::to_string(s) << ", " << ranks << " ranks, tcp " << tcp << ": " << r.audit_failure);
        CHECK(r.exactly_once);
        CHECK(r.efficiency > 0.0);
        CHECK(r.efficiency <= 1.0);
      }
    }
  }
}

// The rma ranks start from contiguous lists, which the moving heavy fifth unbalances (without stealing about a
// quarter efficient here); stealing must bring them to within 10 % of ideal. Static round robin is not the
// bar: interleaving spreads a contiguous heavy fifth evenly (about 0.997 on this workload).
TEST_CASE("simulated stealing steals under skew and balances what its contiguous lists do not", "[rma_simulator]") {
  const auto passes = [](const sim::Result& r) { return r.steals > 0 && r.efficiency >= 0.9; };
  const sim::Result rma = sim::simulate(sim::Scheduler::kRma, 16, small(), shared_memory_like());
  INFO("rma: " << rma.steals << " steals, efficiency " << rma.efficiency);
  CHECK(rma.exactly_once);
  CHECK(passes(rma));
  // Negative control: thieves that plan an empty share (mid = end) steal nothing; the check must fail.
  const sim::Result empty =
      sim::simulate(sim::Scheduler::kRma, 16, small(), shared_memory_like(), 1, sim::Defect::kEmptyShare);
  INFO("empty share: " << empty.steals << " steals, efficiency " << empty.efficiency);
  CHECK(empty.exactly_once);
  CHECK_FALSE(passes(empty));
}

// The cost cascade (synthetic_cost.hpp) concentrates cost in space: static contiguous blocks are far from ideal
// (the workload's own test computes about 0.35 at 4 ranks), and stealing from the same blocks must recover.
TEST_CASE("on the cost cascade simulated stealing recovers what static blocks of space lose", "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 16384;
  const sim::Result blocks = sim::simulate(sim::Scheduler::kStaticSpace, 4, w, shared_memory_like());
  const sim::Result rma = sim::simulate(sim::Scheduler::kRma, 4, w, shared_memory_like());
  INFO("static-space " << blocks.efficiency << ", rma " << rma.efficiency << " (" << rma.steals << " steals)");
  CHECK(blocks.exactly_once);
  CHECK(rma.exactly_once);
  CHECK(blocks.efficiency < 0.7);
  CHECK(rma.efficiency > 0.9);
  CHECK(rma.efficiency > 1.3 * blocks.efficiency);
}

TEST_CASE("negative control: a thief that skips the re-read (T5) is caught by the model's audit", "[rma_simulator]") {
  // Items of 10 ns against operations of 2 us: the victim claims far past mid before T3 lands.
  sim::Latencies lat = shared_memory_like();
  lat.get = lat.put = lat.cas = lat.fetch_op = 2000;
  sim::Workload w = small();
  w.light_ns = 10;
  const sim::Result correct = sim::simulate(sim::Scheduler::kRma, 4, w, lat, 1, sim::Defect::kNone);
  CHECK(correct.exactly_once);
  const sim::Result broken = sim::simulate(sim::Scheduler::kRma, 4, w, lat, 1, sim::Defect::kSkipReread);
  CHECK_FALSE(broken.exactly_once);
  CHECK_THAT(broken.audit_failure, Catch::Matchers::Contains("executed 2 times"));
}

// --plots: one line per latency set and scheduler, ranks in order, the PNG drawn (bootstrap installs gnuplot).
TEST_CASE("the efficiency plot holds one line per latency set and scheduler", "[rma_simulator]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("frontsteal-sim-plot-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const frontsteal::report::Json rows = frontsteal::report::Json::parse(
      R"([{"latencies":"shm","scheduler":"rma","ranks":2,"efficiency":0.99},
          {"latencies":"shm","scheduler":"rma","ranks":16,"efficiency":0.9},
          {"latencies":"tcp","scheduler":"static","ranks":2,"efficiency":1.0}])");
  sim::write_efficiency_plot(dir.string(), rows, "test workload");
  std::ifstream in(dir / "simulated-efficiency.dat");
  const std::string d((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(d == "\"shm rma\"\n2 0.99\n16 0.9\n\n\n\"tcp static\"\n2 1\n\n\n");
  CHECK(fs::file_size(dir / "simulated-efficiency.png") > 1000);
  // hier's loss account: one stacked bar per run, its parts in the account's order.
  const frontsteal::report::Json losses = frontsteal::report::Json::parse(
      R"([{"latencies":"shm","scheduler":"hier","ranks":4,"threads":16,"work":0.9,"claims":0.05,
           "local_steals":0.01,"remote_steals":0.01,"idle":0.02,"tail":0.005,"barrier":0.005}])");
  sim::write_loss_plot(dir.string(), losses, "test workload");
  std::ifstream loss_in(dir / "hier-loss-account.dat");
  const std::string l((std::istreambuf_iterator<char>(loss_in)), std::istreambuf_iterator<char>());
  CHECK(l ==
        "run work claims local_steals remote_steals idle tail barrier\n"
        "\"shm hier 4x16\" 0.9 0.05 0.01 0.01 0.02 0.005 0.005\n");
  CHECK(fs::file_size(dir / "hier-loss-account.png") > 1000);
  fs::remove_all(dir);
}

// The validation compares ratios to static round robin: a measured run that IS the model (its own frame times,
// scaled by a machine factor every scheduler pays alike) is within 10 % everywhere; one scheduler measured 30 %
// slower than the model says is outside, with the error's sign and size.
TEST_CASE("the simulator's validation passes the model's own run and catches a planted 30 % slowdown",
          "[rma_simulator]") {
  sim::MeasuredRun run;
  run.path = "planted";
  run.ranks = 4;
  run.workload = small();
  run.workload.shape = frontsteal::mpi::CostShape::kCascade;
  const sim::Latencies lat = shared_memory_like();
  const double machine = 1.2;  // this machine's items are 20 % slower than nominal: cancels in every ratio
  for (sim::Scheduler s : {sim::Scheduler::kRma, sim::Scheduler::kStatic, sim::Scheduler::kStaticSpace}) {
    const sim::Result r = sim::simulate(s, run.ranks, run.workload, lat);
    run.schedulers.push_back({sim::to_string(s), machine * r.time_ns / run.workload.frames / 1e6});
  }
  for (const sim::ValidationRow& row : sim::validate(run, lat)) {
    INFO(row.scheduler);
    CHECK(std::abs(row.ratio_error) < 1e-9);
  }
  run.schedulers[0].median_frame_ms *= 1.3;  // rma measured 30 % slower than the model
  const std::vector<sim::ValidationRow> rows = sim::validate(run, lat);
  REQUIRE(rows[0].scheduler == "rma");
  CHECK(rows[0].ratio_error == Approx(1 / 1.3 - 1).epsilon(1e-9));
  CHECK(std::abs(rows[0].ratio_error) > 0.10);
  CHECK(std::abs(rows[2].ratio_error) < 1e-9);       // the others unchanged
  run.schedulers.erase(run.schedulers.begin() + 1);  // no static round robin: nothing to relate to
  CHECK_THROWS_WITH(sim::validate(run, lat), Catch::Contains("no static"));
}

// hier (ranks x threads): exactly once with local and remote steals, on both transports; its loss account
// covers every worker's whole time (work + losses = ranks x threads x time); the planted skip-reread of the
// remote thief is caught under hier too.
TEST_CASE("simulated hier runs each item once and accounts for every worker's time", "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 16384;
  for (const bool tcp : {false, true}) {
    sim::Latencies lat = shared_memory_like();
    lat.needs_target_progress = tcp;
    for (sim::Scheduler s : {sim::Scheduler::kHier, sim::Scheduler::kHierSeeded}) {
      for (const auto& [ranks, threads, lifelines] :
           {std::tuple{2, 1, true}, {4, 4, true}, {16, 8, true}, {4, 4, false}, {16, 8, false}}) {
        w.threads = threads;
        w.lifelines = lifelines;
        const sim::Result r = sim::simulate(s, ranks, w, lat);
        INFO(sim::to_string(s) << " " << ranks << " x " << threads << ", tcp " << tcp << ", lifelines " << lifelines
                               << ": " << r.audit_failure);
        CHECK(r.exactly_once);
        CHECK(r.threads == threads);
        CHECK(r.loss.work == Approx(r.work_ns).epsilon(1e-9));
        CHECK(r.loss.total() == Approx(static_cast<double>(ranks) * threads * r.time_ns).epsilon(1e-6));
        CHECK(r.efficiency > 0.0);
        CHECK(r.efficiency <= 1.0);
        if (threads > 1) CHECK(r.local_steals > 0);
        if (ranks > 2 && s == sim::Scheduler::kHier) CHECK(r.steals > 0);
      }
    }
  }
  sim::Latencies slow = shared_memory_like();  // operations of 2 us against items of 10 ns, as above
  slow.get = slow.put = slow.cas = slow.fetch_op = 2000;
  sim::Workload tiny = small();
  tiny.light_ns = 10;
  tiny.threads = 2;
  tiny.lifelines = false;  // rounds of random victims: steals enough, on this tiny workload, to hit the overlap
  CHECK(sim::simulate(sim::Scheduler::kHier, 4, tiny, slow, 1, sim::Defect::kNone).exactly_once);
  const sim::Result broken = sim::simulate(sim::Scheduler::kHier, 4, tiny, slow, 1, sim::Defect::kSkipReread);
  CHECK_FALSE(broken.exactly_once);
}

// Stealing inside and across ranks recovers what static blocks of space lose on the cascade, and threads share a
// rank's work: 4 ranks x 4 threads within 15 % of ideal where the blocks reach less than half. Control: thieves
// that plan empty remote shares leave the blocks' imbalance in place (local stealing cannot move work between
// ranks), and the check fails.
TEST_CASE("simulated hier recovers what static blocks of space lose, and needs its remote steals to",
          "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 65536;
  w.threads = 4;
  const auto passes = [](const sim::Result& r) { return r.exactly_once && r.efficiency > 0.85; };
  const sim::Result blocks = sim::simulate(sim::Scheduler::kStaticSpace, 4, w, shared_memory_like());
  const sim::Result hier = sim::simulate(sim::Scheduler::kHier, 4, w, shared_memory_like());
  const sim::Result empty =
      sim::simulate(sim::Scheduler::kHier, 4, w, shared_memory_like(), 1, sim::Defect::kEmptyShare);
  INFO("static-space " << blocks.efficiency << ", hier " << hier.efficiency << " (" << hier.steals << " remote, "
                       << hier.local_steals << " local steals), empty shares " << empty.efficiency);
  CHECK(blocks.efficiency < 0.5);
  CHECK(passes(hier));
  CHECK(empty.exactly_once);
  CHECK_FALSE(passes(empty));
  const auto [part, share] = hier.loss.bottleneck();
  CHECK(share > 0.0);
  CHECK(std::string(part) != "none");
}

// LIFELINES: a dry rank that found nothing in one round waits on its own words, so the remote attempts fall
// (against rounds with back-off, same workload and seed), every item still runs once, and every worker learns
// the frame is over. The model's termination audit counts only because it catches the planted defect: a rank
// that learns the frame is over tells nobody, and the ranks waiting on their lifelines never finish.
TEST_CASE("simulated lifelines: dry ranks wait quietly, and the frame's end reaches every rank", "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 65536;
  w.threads = 4;
  w.lifelines = true;
  const sim::Result on = sim::simulate(sim::Scheduler::kHierSeeded, 64, w, shared_memory_like());
  w.lifelines = false;
  const sim::Result off = sim::simulate(sim::Scheduler::kHierSeeded, 64, w, shared_memory_like());
  INFO("remote attempts with lifelines " << on.steal_attempts << ", without " << off.steal_attempts << "; efficiency "
                                         << on.efficiency << " / " << off.efficiency);
  CHECK(on.exactly_once);
  CHECK(off.exactly_once);
  CHECK(on.steals > 0);
  CHECK(on.steal_attempts * 2 < off.steal_attempts);
  w.lifelines = true;
  w.threads = 1;  // with siblings the waiting ranks' threads would poll forever: the model's event limit
  const sim::Result dropped =
      sim::simulate(sim::Scheduler::kHierSeeded, 64, w, shared_memory_like(), 1, sim::Defect::kLifelineDropsNotice);
  INFO("dropped notice: " << dropped.audit_failure);
  CHECK_FALSE(dropped.exactly_once);
  CHECK_THAT(dropped.audit_failure, Catch::Contains("never learned the frame was over"));
}

// Batch claims: a refill that holds the rank mutex for one claim per run of consecutive ids instead of one per
// item spends less of the workers' time on claims.
TEST_CASE("simulated batch claims spend less time claiming", "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 65536;
  w.threads = 16;
  w.batch_claims = false;
  const sim::Result one_by_one = sim::simulate(sim::Scheduler::kHierSeeded, 4, w, shared_memory_like());
  w.batch_claims = true;
  const sim::Result batched = sim::simulate(sim::Scheduler::kHierSeeded, 4, w, shared_memory_like());
  INFO("claims " << one_by_one.loss.claims << " ns one by one, " << batched.loss.claims << " ns batched");
  CHECK(batched.exactly_once);
  CHECK(batched.loss.claims < one_by_one.loss.claims);
}

// The first frame knows no item's cost and starts from blocks of space, so a few ranks hold every heavy item.
// A refill that priced unknown items at a mean took tens of heavy items into one worker's local list, where no
// other rank can take them, and that rank's threads ran the frame's tail alone. refill_budget.hpp measures
// before it commits: the first frame is then within a quarter of a later one (1.09 times). Pricing unknown
// items at the rank's mean instead gives 1.62 times on this configuration, and this test fails on it.
TEST_CASE("simulated hier: a first frame of unknown costs does not strand heavy items in one rank", "[rma_simulator]") {
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 2097152;
  w.threads = 16;
  w.frames = 2;
  const sim::Result hier = sim::simulate(sim::Scheduler::kHier, 128, w, shared_memory_like());
  REQUIRE(hier.frame_ns.size() == 2);
  INFO("first frame " << hier.frame_ns[0] << " ns, second " << hier.frame_ns[1] << " ns");
  CHECK(hier.exactly_once);
  CHECK(hier.frame_ns[0] < 1.25 * hier.frame_ns[1]);
}

// The workload's own limits, against a schedule worked out by hand: items 3, 3, 2, 2, 2 on 2 workers. Greedy in
// id order: 3 | 3, then 2 to the first, 2 to the second, 2 to the first: 7. Longest first is the same order: 7.
// The bound: max(12 / 2, 3) = 6. And on the cascade at 256 x 16 workers no schedule beats the bound.
TEST_CASE("the workload's limits: greedy, longest first and the bound, by hand", "[rma_simulator]") {
  const sim::WorkloadLimits hand = sim::workload_limits({{3, 3, 2, 2, 2}}, 2);
  CHECK(hand.max_item_ns == 3);
  CHECK(hand.bound == Approx(1.0));
  CHECK(hand.greedy == Approx(12.0 / 14.0));
  CHECK(hand.lpt == Approx(12.0 / 14.0));
  const sim::WorkloadLimits skewed = sim::workload_limits({{1, 1, 1, 1, 8}}, 4);  // one item outweighs a share
  CHECK(skewed.bound == Approx(12.0 / (4 * 8.0)));
  CHECK(skewed.greedy == Approx(12.0 / (4 * 9.0)));  // the heavy item last, after a light one
  CHECK(skewed.lpt == Approx(skewed.bound));         // longest first reaches the bound here
  sim::Workload w = small();
  w.shape = frontsteal::mpi::CostShape::kCascade;
  w.items = 65536;
  const sim::WorkloadLimits cascade = sim::workload_limits(w, 64);
  CHECK(cascade.greedy <= cascade.bound + 1e-12);
  CHECK(cascade.lpt <= cascade.bound + 1e-12);
  CHECK(cascade.greedy > 0.5);
}
