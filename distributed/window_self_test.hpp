// window_self_test.hpp — before any frame, every one-sided operation the protocols use is checked against
// values known in advance, on the transport this run actually got.
//
// WHY. The protocols trust each operation's RESULT: a thief decides from T1/T2's Gets whether there is work,
// from L2's compare-and-swap whether it holds the lock; the termination count and the central counter are
// fetch-and-ops. A window that reads a result before MPI_Win_flush passes on one node: Open MPI's osc/sm
// (one node) copies inside MPI_Get, so nothing showed and every test passed; over osc/pt2pt (TCP, two hosts)
// the data arrives at the flush, so every result was 0: thieves saw empty lists (no steal over TCP in any
// run), the lock CAS always "succeeded", the central counter handed out item 0 forever (the "hang"). The
// exactly-once audit could not see it: a thief that never steals executes nothing twice.
//
// WHAT IT CHECKS. Turn by turn, rank t (the origin) operates on rank q = t + 1 (mod P), whose words hold
// values no other code writes (0xF00D0000 + q in Front, 0x10C00000 + q in LockList, 0xC0DE0000 + q in the entry
// count, a marked entry 0 in the list body): L1's fetch-and-op MPI_NO_OP, T1's Get, the entry count's Get,
// L2's compare-and-swap (expected = the value there: it must report finding it), T3's Put (q then reads it
// locally), the list body's multi-word Get, A1's fetch-and-op MPI_SUM on rank 0's 32-bit count, and the
// central counter's 64-bit MPI_SUM (a base beyond 2^32). The target sleeps kTargetAsleep (no MPI call) once
// it leaves the turn's barrier, so on a transport that needs the target's progress (osc/pt2pt) the origin's
// first operation can complete early only if the target answers within the microseconds between the two
// leaving the barrier AND the reply is processed inside the very MPI call that sent the request — not seen in
// any run here; a result read early is then wrong. Every word is reset afterwards (install's L2 would spin on
// a LockList left non-zero). Cost: P turns of kTargetAsleep plus a few round trips (~25 ms per rank).
//
// ITS NEGATIVE CONTROL: --plant-defect read-before-flush (RmaWindow::plant_read_before_flush) with
// --mca osc pt2pt must fail here (tests/CMakeLists.txt, distributed.mpi.control_read_before_flush_caught).
// On osc/sm the same defect passes — there it is harmless, because the copy happens inside MPI_Get.
#pragma once

#include <mpi.h>

#include <chrono>
#include <string>

#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

inline constexpr std::chrono::milliseconds kTargetAsleep{20};

struct WindowSelfTest {
  bool ok = true;
  std::string first_failure;  // this rank's first wrong result, "" when ok (every rank learns `ok`)
};

// Collective over comm (the window's communicator); leaves every word it touched as it found it (zero).
WindowSelfTest run_window_self_test(RmaWindow& win, MPI_Comm comm);

}  // namespace frontsteal::mpi
