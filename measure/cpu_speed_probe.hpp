// cpu_speed_probe.hpp — did the CPU itself change speed between repeats? A fixed arithmetic loop timed beside
// every serial pass, so that a spread of the serial loop's repeats can be told apart: the machine (the core
// ran slower) or the program (the same core, a different time).
//
// Why: on every machine lent to this work (two 2-vCPU VMs, a 16-vCPU VM) the serial loop's repeats spread by
// 14–76 % with nothing else running — /proc saw no other process and no steal, and the thread was on its CPU
// the whole time. /proc cannot see what slows a vCPU that keeps running: a lower host clock, or a busy SMT
// sibling on the host's physical core. A probe can: its work is fixed — eight independent chains of integer
// multiply-add and shift-xor steps (the same instructions every call, no memory traffic, no branches that
// depend on data), enough of them to keep the multiplier busy, so a busy SMT sibling competing for it slows the
// probe as a lower clock does — and its wall time per step moves only when the core retires those instructions
// more slowly, or when the thread loses the core. The main job takes it on the harness thread just before every
// arm of every round (the covariate of paired_analysis.hpp); for the spread diagnosis, the smallest probe taken
// before the serial loop's segments of a pass stands for that pass (a lost time slice inflates one probe, not the
// speed of the core).
//
// What it cannot see: contention for memory bandwidth or the last-level cache (the probe touches neither). For
// that, pass_usage.hpp: when every pass did the same work on its CPU (no page fault, no system time, never
// blocked, on the CPU for its whole wall time), the same instructions took longer — the hardware's speed or
// state, whatever the probe says. The diagnosis never calls anything "the program's" or "the machine's" beyond
// what those two measurements show.
//
// The decision (diagnose_spread) is pure, so tests drive it with synthetic repeats; probe_ns_per_million_steps()
// is the only part that measures, and its checks are a chain the compiler dropped (it would report ~0 ns) and a
// probe stopped by SIGSTOP that must report the lost time (tests/measure/cpu_speed_probe_test.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "measure/pass_usage.hpp"

namespace frontsteal::noise {

// Steps of one probe: 2–3 ms on a 2020s core (a step is eight multiply-adds and eight shift-xors).
inline constexpr std::uint64_t kProbeSteps = 1'000'000;

// Runs `steps` steps of the chains on the calling thread; wall-clock ns per million steps.
double probe_ns_per_million_steps(std::uint64_t steps = kProbeSteps);

struct SpreadDiagnosis {
  double serial_spread = 0;           // max / min − 1 of the serial passes
  double probe_spread = 0;            // max / min − 1 of the probe, one value per pass
  double correlation = 0;             // Pearson r between a pass's time and its probe (0 with fewer than 3 passes)
  bool cpu_varied = false;            // the probe spread by more than the threshold
  bool probe_follows_passes = false;  // ... by at least half the serial spread, r >= 0.7 over >= 3 passes: the
                                      // core's speed explains the spread
  bool same_work_on_cpu = false;      // every pass did the same work on its CPU (pass_usage.hpp)
  std::string line;                   // one sentence for the report
};

// `serial_ms[k]` is the k-th serial pass, `probe[k]` the probe around it (same length), `passes[k]` what the
// pass's thread did (empty: not measured); `threshold` is the spread above which a change counts (the noise
// monitor's --noise-spread).
SpreadDiagnosis diagnose_spread(const std::vector<double>& serial_ms, const std::vector<double>& probe,
                                double threshold, const std::vector<PassUsage>& passes = {});

}  // namespace frontsteal::noise
