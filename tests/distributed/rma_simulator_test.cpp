// rma_simulator_test.cpp — the distributed simulator's own audit (rma_simulator.hpp): every scheduler runs
// each item exactly once per frame, with and without the transport's target-progress delay, and the planted
// skip-reread defect is caught (deterministic: a fixed seed and a configuration where victims run many
// items between a thief's T1 and T3).
#include <catch2/catch.hpp>

#include "distributed/rma_simulator.hpp"

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
                             sim::Scheduler::kStatic}) {
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

TEST_CASE("simulated stealing steals under skew and beats static round robin's worst case", "[rma_simulator]") {
  const sim::Result rma = sim::simulate(sim::Scheduler::kRma, 16, small(), shared_memory_like());
  CHECK(rma.steals > 0);
  CHECK(rma.exactly_once);
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
