// pass_usage.hpp — what one measured pass's own thread did, from getrusage(RUSAGE_THREAD): user and system
// time, page faults, voluntary and involuntary context switches.
//
// Why: when the serial loop's repeats spread, the question is whether the program did different work (page
// faults, system calls, blocking) or the same work ran slower on the hardware. The serial pass is
// deterministic — the same surfaces, the same steps, the same buffers reused — so when every pass ran in user
// mode only (no fault, no system time to speak of, never blocked), a slower pass is the hardware's doing: a
// lower clock, a busy SMT sibling, or caches and memory shared with other tenants of the host. Measured on a
// 2-vCPU VM (12 passes): 0 page faults, 0 ms system time, 0 voluntary and 2–6 involuntary switches
// per pass, user time within 1 % of wall time — and still one pass 18 % slower than the others.
#pragma once

#include <sys/resource.h>

#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace frontsteal::noise {

struct PassUsage {
  double wall_ms = 0, user_ms = 0, system_ms = 0;
  long faults = 0;                // minor + major page faults
  long voluntary_switches = 0;    // the thread blocked (a lock, I/O, a sleep)
  long involuntary_switches = 0;  // the scheduler took the CPU away (a tick, another runnable task)
  // A pass measured in pieces (one per round's segment) is the sum of its pieces.
  PassUsage& operator+=(const PassUsage& o) {
    wall_ms += o.wall_ms;
    user_ms += o.user_ms;
    system_ms += o.system_ms;
    faults += o.faults;
    voluntary_switches += o.voluntary_switches;
    involuntary_switches += o.involuntary_switches;
    return *this;
  }
};

// Started on the thread that runs the pass; stop() on the same thread.
class PassMeter {
 public:
  PassMeter();
  PassUsage stop() const;

 private:
  rusage start_{};
  std::chrono::steady_clock::time_point t0_;
};

// True when every pass did the same work on its CPU: no page fault, never blocked, system time under 1 % of
// its wall time (the tick accounting of an idle kernel), and on the CPU (user + system) for at least 98 % of it
// (not preempted for long). False for an empty list.
bool same_work_on_cpu(const std::vector<PassUsage>& passes);

// The passes as columns for the results files: {"wall_ms": [...], "user_ms": [...], ...}, one value per pass
// (every key present, with empty arrays when there are no passes).
std::map<std::string, std::vector<double>> pass_usage_columns(const std::vector<PassUsage>& passes);

}  // namespace frontsteal::noise
