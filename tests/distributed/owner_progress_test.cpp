// distributed/owner_progress.hpp's PollGate: the time gate of the busy rma owner's progress call, the request
// owner's poll and rank 0's calls inside central-counter chunks. The clock is the test's: instants are made
// here, so nothing depends on how fast the machine runs.
#include <catch2/catch.hpp>

#include <chrono>

#include "distributed/owner_progress.hpp"

namespace mpi = frontsteal::mpi;
using Clock = mpi::PollGate::Clock;
using std::chrono::microseconds;

TEST_CASE("a gate of U microseconds opens at most once every U", "[distributed][owner_progress]") {
  mpi::PollGate gate(50);
  CHECK(gate.enabled());
  const Clock::time_point t0 = Clock::now();
  CHECK(gate.due(t0));  // the first call is due at once
  CHECK_FALSE(gate.due(t0 + microseconds(1)));
  CHECK_FALSE(gate.due(t0 + microseconds(49)));
  CHECK(gate.due(t0 + microseconds(50)));  // U after the last one
  CHECK_FALSE(gate.due(t0 + microseconds(99)));
  CHECK(gate.due(t0 + microseconds(400)));  // a long item: due once, not once per missed interval
  CHECK_FALSE(gate.due(t0 + microseconds(401)));
}

TEST_CASE("a gate of 0 opens after every item, a negative one never", "[distributed][owner_progress]") {
  mpi::PollGate every(0);
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 5; ++i) CHECK(every.due(t0));  // the same instant: still every time
  mpi::PollGate never(-1);
  CHECK_FALSE(never.enabled());
  CHECK_FALSE(never.due(t0));
  CHECK_FALSE(never.due(t0 + std::chrono::hours(1)));
}

TEST_CASE("the auto interval is the one the TCP sweep chose", "[distributed][owner_progress]") {
  // docs/mpi.md and results/distributed/owner_progress_sweep_tcp.txt: 50 us keeps a steal within a few ms.
  CHECK(mpi::kAutoProgressEveryUs == 50);
}
