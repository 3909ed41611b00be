// owner_progress.hpp — the busy rma owner's cheap call into MPI, so that one-sided operations aimed at it
// complete on transports without asynchronous progress.
//
// WHY. Passive-target RMA needs the target's help on some transports. Open MPI 4.1 picks osc/sm when every
// rank of the window shares one node's memory: a Get is then a load by the origin, nothing waits for the
// target. Across TCP the only component this build can use is osc/pt2pt (osc/rdma needs an RDMA-capable BTL,
// osc/ucx UCX's network transports): each Get/Put/CAS is a message that the TARGET's progress engine must
// receive and answer, and Open MPI runs that engine only inside MPI calls of the target. A busy owner that
// claims with plain loads and stores (G2 of rma_window.hpp) makes no MPI call until its list is exhausted.
// The standard allows this (MPI 3.1 §11.7.3: an RMA operation completes once the target calls into MPI).
//
// WHAT THIS DOES. The owner calls MPI_Iprobe (on a tag nobody sends) between items, at most every `every_us`
// microseconds (0: after every item); MPI_Iprobe runs opal_progress, which polls btl/tcp's sockets. The
// request owner's poll and rank 0 inside central-counter chunks use the same gate (PollGate). Cost, measured
// by --calibrate ("owner progress call"): 98 ns on osc/sm, 3.2 us over TCP (5.3 us with mpi_yield_when_idle).
// auto = off when the library is Open MPI, every rank shares one node and no --mca osc other than sm is set
// (osc/sm); otherwise every kAutoProgressEveryUs, with or without a progress thread.
// WHY AN INTERVAL (measured, docs/mpi.md "Two hosts"; 2 ranks over TCP, 1 us light items): a call after EVERY item
// mostly left a thief's operations, and request messages, unanswered until the victim ran dry (0, 3 and 0
// steals in three 10-frame runs; the cause inside Open MPI was not pinned down), while every 10-200 us gave
// 21-37 steals, the mean steal latency growing with the interval (~0.5 ms at 10 us, 2.2 ms at 50 us, 7-11 ms
// at 200 us) and the owner's overhead shrinking (frame 236 ms at 10 us, 201 ms at 50 us, 190 ms with no
// calls; results/distributed/owner_progress_sweep_tcp.txt). 50 us keeps a steal within a few ms.
// Stealing over TCP works once every result is read after its flush (rma_window.hpp, G1): a thief that
// never steals over TCP is a read-before-flush bug, not the transport.
//
// A progress THREAD (progress_thread.hpp, --progress-thread) serves operations whatever the workers do, but needs
// MPI_THREAD_MULTIPLE, which osc/pt2pt refuses in Open MPI 4.1 (over TCP: osc/ucx), and takes time from the
// workers on a machine with fewer cores than threads. auto keeps these calls beside it: over TCP on this 2-vCPU
// VM a yielding thread alone was scheduled about once per 0.4 ms and steals took 1.2-1.4 ms; with the owner's
// calls as well, 0.7 ms (docs/mpi.md, "A progress thread per rank").
#pragma once

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace frontsteal::mpi {

inline constexpr int kTagProgressProbe = 183;  // never sent: the probe only drives progress
// auto's interval where a transport needs the target's progress (see WHY AN INTERVAL above).
inline constexpr double kAutoProgressEveryUs = 50;

// At most once every `every_us` microseconds (0: every time; < 0: never): the time gate of the rma owner's
// progress call and of the request owner's poll for steal requests.
class PollGate {
 public:
  using Clock = std::chrono::steady_clock;
  explicit PollGate(double every_us)
      : every_(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double, std::micro>(every_us < 0 ? 0 : every_us))),
        enabled_(every_us >= 0) {}
  bool due(Clock::time_point now) {
    if (!enabled_ || now < next_) return false;
    next_ = now + every_;
    return true;
  }
  bool enabled() const noexcept { return enabled_; }

 private:
  Clock::duration every_;
  bool enabled_;
  Clock::time_point next_{};
};

class OwnerProgress {
 public:
  using Clock = PollGate::Clock;
  // every_us < 0: never; 0: every item; > 0: at most every every_us microseconds.
  OwnerProgress(MPI_Comm comm, double every_us) : comm_(comm), gate_(every_us) {}

  // Between two items, with the time already read; returns whether it called into MPI.
  bool maybe_call(Clock::time_point now) {
    if (!gate_.due(now)) return false;
    call();
    return true;
  }
  void call() {
    int flag = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagProgressProbe, comm_, &flag, MPI_STATUS_IGNORE);
    ++calls_;
  }
  std::uint64_t calls() const noexcept { return calls_; }
  bool enabled() const noexcept { return gate_.enabled(); }

 private:
  MPI_Comm comm_;
  PollGate gate_;
  std::uint64_t calls_ = 0;
};

// What the run uses: the --owner-progress value resolved ("auto" by the rule above), and a line saying which
// osc component was asked for (Open MPI: OMPI_MCA_osc, which mpirun's --mca osc sets) and whether every rank
// shares one node. Collective over comm.
struct ProgressChoice {
  double every_us = -1;         // < 0: off
  double thread_sleep_us = -1;  // the rank's progress thread (progress_thread.hpp) sleeps this long; < 0: none
  bool one_node = false;
  bool open_mpi = false;      // MPI_Get_library_version starts with "Open MPI"
  std::string osc_requested;  // "" when the launcher did not say
  std::string describe() const;
};
// thread_sleep_us: --progress-thread resolved (< 0: no thread).
ProgressChoice resolve_owner_progress(const std::string& option, double thread_sleep_us, MPI_Comm comm);

}  // namespace frontsteal::mpi
