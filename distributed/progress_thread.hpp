// progress_thread.hpp — a thread of the rank's own that calls into MPI, so that one-sided operations aimed at
// the rank complete while its workers run items, whatever those workers are doing.
//
// WHY. On transports without asynchronous progress (TCP: owner_progress.hpp says why) a thief's operation
// waits until the victim's process next enters MPI. The busy owner's gated MPI_Iprobe (owner_progress.hpp)
// serves it between items, at most every 50 us; a worker descheduled or inside a long item serves nothing.
// This thread serves it within one of its own sleeps, independent of the workers.
//
// NEEDS MPI_THREAD_MULTIPLE: its calls run beside the main thread's. frontsteal-mpi asks for that level when
// the thread is wanted and refuses to run below it. Open MPI 4.1's osc/pt2pt (its only one-sided component over
// TCP without UCX) refuses that level: the window's allocation fails, and frontsteal-mpi says so. osc/ucx
// (UCX, its TCP transport included) and osc/sm accept it.
//
// COST. A thread that never sleeps (0) takes time from the workers on a machine with fewer cores than
// threads; sleeping S us between calls adds the kernel's timer slack (about 50 us on Linux) to each sleep. On
// the 2-vCPU VM, over TCP, yielding cost each frame 3-5 ms and left the steal latency where the owner's own calls
// had it; sleeping 50 us made frames 2-3x longer, for reasons not pinned down (docs/mpi.md, "A progress thread
// per rank"). The thread does not feed the watchdog: a rank whose workers hang still trips it.
#pragma once

#include <mpi.h>

#include <atomic>
#include <cstdint>
#include <thread>

namespace frontsteal::mpi {

class ProgressThread {
 public:
  // Starts calling MPI_Iprobe on `comm` (on a tag nobody sends), sleeping `sleep_us` microseconds between
  // calls (0: yielding the core instead). The caller has MPI_THREAD_MULTIPLE.
  ProgressThread(MPI_Comm comm, double sleep_us);
  ~ProgressThread();  // stops the loop and joins it
  ProgressThread(const ProgressThread&) = delete;
  ProgressThread& operator=(const ProgressThread&) = delete;

  std::uint64_t calls() const noexcept { return calls_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> calls_{0};
  std::thread thread_;
};

}  // namespace frontsteal::mpi
