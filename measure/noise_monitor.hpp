// noise_monitor.hpp — was the machine quiet while we measured? A monitor that samples the kernel's counters
// around every measured path and says when the answer is no.
//
// What it reads (proc(5)):
//   /proc/stat, line "cpu"   machine-wide ticks since boot: user nice system idle iowait irq softirq steal …
//   /proc/self/stat          our own utime + stime (fields 14 and 15), in the same ticks (sysconf(_SC_CLK_TCK))
//   /proc/loadavg            the 1-minute load average (context only: it lags by a minute and counts our threads)
// Between two samples: the machine's busy ticks (user … softirq) minus ours are the *other processes'* CPU
// time; steal is time a hypervisor gave our vCPUs to someone else. Either, as a share of all ticks of the
// window, above a threshold (default 10 % and 5 %) means we shared the machine. Ticks are coarse (10 ms), so a
// window also needs at least kMinOtherTicks ticks of others' work before it counts as busy: a quiet
// 20 ms window must not be flagged by one stray tick.
//
// A process of ours that is known to take CPU on purpose (the interference co-runner, interference.hpp) is
// not "other processes": sample_now(pid) also reads its utime + stime from /proc/<pid>/stat (known_ticks),
// and other_ticks() leaves them out, so the co-runner is reported on its own (known_share) while any
// genuinely external load is still flagged.
// Our other child processes (the openmp-static-steal child of llvm_openmp_child.hpp, which loads the scene
// while we do and runs its own rows; gnuplot) are ours too: sample_now() adds up the utime + stime of every
// live process whose parent is this process (a scan of /proc/<pid>/stat; children_ticks), so a run is not
// called busy because of work it started itself. (Before this, the static-steal child's scene loading made
// the "before" window read ~20 % "other processes" on every default run, quiet machine or not.) A child that
// exits inside a window takes its ticks out of the sum; the delta is then clamped to 0, so that window
// counts the child's last ticks as other (errs towards "busy", never towards "quiet").
//
// The decision (assess, spread_of) is pure, over parsed samples, so tests drive it with synthetic
// /proc text for both a quiet and a loaded machine; sample_now() is the only part that reads files.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace frontsteal::noise {

struct ProcSample {
  bool ok = false;                // every file parsed
  std::uint64_t total_ticks = 0;  // all columns of the "cpu" line
  std::uint64_t busy_ticks = 0;   // user + nice + system + irq + softirq (guest time is inside user)
  std::uint64_t steal_ticks = 0;
  std::uint64_t self_ticks = 0;      // this process: utime + stime
  std::uint64_t known_ticks = 0;     // the known co-runner's utime + stime (0 when none, or gone)
  std::uint64_t children_ticks = 0;  // our other live child processes' utime + stime
  double load1 = 0;                  // 1-minute load average
  double wall_s = 0;                 // steady clock when sampled
};

// Parses the text of /proc/stat, /proc/self/stat and /proc/loadavg; ok = false if any is malformed.
ProcSample parse_sample(std::string_view proc_stat, std::string_view self_stat, std::string_view loadavg,
                        double wall_s);
// Reads the three files now, /proc/<known>/stat when known > 0 (the co-runner; see above), and the stat
// files of our other live children.
ProcSample sample_now(pid_t known = 0);
// utime + stime of every live process whose parent is `parent`, except `except` (a scan of /proc).
std::uint64_t children_ticks(pid_t parent, pid_t except);

// What happened between two samples; windows add up (a verdict depends on many short windows).
struct Usage {
  std::uint64_t total_ticks = 0, busy_ticks = 0, steal_ticks = 0, self_ticks = 0, known_ticks = 0;
  std::uint64_t children_ticks = 0;
  double wall_s = 0;
  int windows = 0;
  bool ok = true;
  Usage& operator+=(const Usage& o);
  std::uint64_t other_ticks() const;  // busy − self − known − children, never negative (the counters round differently)
  double known_share() const;         // the known co-runner's, of all ticks in the window(s)
  double other_share() const;         // of all ticks in the window(s)
  double steal_share() const;
};
Usage usage_between(const ProcSample& before, const ProcSample& after);

struct Thresholds {
  double other_share = 0.10;  // others' CPU, as a share of the machine
  double steal_share = 0.05;
  double spread = 0.05;  // serial loop's repeats: max / min − 1
};
inline constexpr std::uint64_t kMinOtherTicks = 5;  // 50 ms at the usual 100 Hz

struct Assessment {
  bool busy = false;
  std::string reason;  // empty when quiet
};
Assessment assess(const Usage& u, const Thresholds& t);

// max / min − 1 of positive values (0 for fewer than two).
double spread_of(const std::vector<double>& values);

// A share as the reports print it: 0.123 -> "12.3 %".
std::string percent(double share);

}  // namespace frontsteal::noise
