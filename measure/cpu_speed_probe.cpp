// cpu_speed_probe.cpp — the probe and the spread diagnosis (cpu_speed_probe.hpp).
#include "measure/cpu_speed_probe.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "measure/noise_monitor.hpp"

namespace frontsteal::noise {

namespace {

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n, my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

}  // namespace

double probe_ns_per_million_steps(std::uint64_t steps) {
  if (steps == 0) steps = 1;
  // Eight independent chains. One step of a chain is a multiply-add and a shift-xor, ~6 cycles of latency with
  // one multiply in it; eight chains put ~8 multiplies in those cycles, so the core's multiplier is the limit
  // (throughput-bound): a busy SMT sibling competing for it slows the probe as a lower clock does, where a lone
  // latency-bound chain would barely notice.
  std::uint64_t x[8] = {0x9e3779b97f4a7c15ull, 0xbf58476d1ce4e5b9ull, 0x94d049bb133111ebull, 0x2545f4914f6cdd1dull,
                        0xd6e8feb86659fd93ull, 0xa0761d6478bd642full, 0xe7037ed1a0b428dbull, 0x8ebc6af09c88c6e3ull};
  const auto t0 = std::chrono::steady_clock::now();
  // The chains' values "change" here and are "used" before t1, so the compiler can neither start the loop
  // before t0 nor finish it after t1, nor drop it (the "memory" clobbers keep the order with the clock calls).
  asm volatile(""
               : "+r"(x[0]), "+r"(x[1]), "+r"(x[2]), "+r"(x[3]), "+r"(x[4]), "+r"(x[5]), "+r"(x[6]), "+r"(x[7])
               :
               : "memory");
  for (std::uint64_t i = 0; i < steps; ++i) {
    for (std::uint64_t& v : x) {
      v = v * 6364136223846793005ull + 1442695040888963407ull;
      v ^= v >> 29;
    }
  }
  asm volatile(""
               :
               : "r"(x[0]), "r"(x[1]), "r"(x[2]), "r"(x[3]), "r"(x[4]), "r"(x[5]), "r"(x[6]), "r"(x[7])
               : "memory");
  const auto t1 = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(t1 - t0).count() * 1e6 / static_cast<double>(steps);
}

SpreadDiagnosis diagnose_spread(const std::vector<double>& serial_ms, const std::vector<double>& probe,
                                double threshold, const std::vector<PassUsage>& passes) {
  SpreadDiagnosis d;
  d.serial_spread = spread_of(serial_ms);
  if (probe.size() != serial_ms.size() || probe.empty()) {
    d.line = "CPU speed probe: not measured";
    return d;
  }
  d.probe_spread = spread_of(probe);
  d.correlation = probe.size() >= 3 ? pearson(serial_ms, probe) : 0.0;
  d.cpu_varied = d.probe_spread > threshold;
  d.probe_follows_passes =
      d.cpu_varied && d.probe_spread >= 0.5 * d.serial_spread && probe.size() >= 3 && d.correlation >= 0.7;
  d.same_work_on_cpu = passes.size() == serial_ms.size() && same_work_on_cpu(passes);
  char r[32];
  std::snprintf(r, sizeof r, "%.2f", d.correlation);
  const std::string probe_says = "a fixed arithmetic loop timed before each serial pass's segments spread " +
                                 percent(d.probe_spread) + " (correlation with the passes r = " + r + ")";
  std::string work_says;  // what the passes' own threads did, when measured
  if (passes.size() == serial_ms.size() && !passes.empty()) {
    long faults = 0, blocked = 0, preempted = 0;
    double system_ms = 0, off_cpu = 0;
    for (const PassUsage& p : passes) {
      faults += p.faults;
      blocked += p.voluntary_switches;
      preempted = std::max(preempted, p.involuntary_switches);
      system_ms += p.system_ms;
      if (p.wall_ms > 0) off_cpu = std::max(off_cpu, 1 - (p.user_ms + p.system_ms) / p.wall_ms);
    }
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "%ld page faults, %.0f ms system time, %ld blocking waits in all passes; at most "
                  "%ld involuntary switches and %.1f %% of the wall time off the CPU in one",
                  faults, system_ms, blocked, preempted, 100 * std::max(0.0, off_cpu));
    work_says = buf;
  }
  if (d.serial_spread <= threshold) {
    d.line = "CPU speed probe: " + probe_says;
  } else if (d.probe_follows_passes) {
    d.line = "the CPU itself changed speed between repeats: " + probe_says + ", most of the serial loop's " +
             percent(d.serial_spread) +
             "; /proc cannot see this (a lower host clock or a busy SMT sibling on the host)";
  } else if (d.same_work_on_cpu) {
    d.line = "every serial pass did the same work on its CPU (" + work_says + ") and still spread " +
             percent(d.serial_spread) +
             ": the same instructions took longer — the hardware's speed or state (a lower "
             "clock, a busy SMT sibling, caches or memory shared with other tenants, or caches left cold by the run "
             "before), not different work by the program; " +
             probe_says;
  } else if (d.cpu_varied) {
    d.line = "the CPU's speed changed between repeats, but it does not explain the serial loop's " +
             percent(d.serial_spread) + ": " + probe_says +
             "; the rest is memory, caches, the program, or time off the CPU" +
             (work_says.empty() ? "" : " (" + work_says + ")");
  } else {
    d.line = "the CPU's speed did not change at the edges of the passes (" + probe_says +
             "): the serial loop's own time varied — memory, caches, the program or time off the CPU, not the core's "
             "clock" +
             (work_says.empty() ? "" : " (" + work_says + ")");
  }
  return d;
}

}  // namespace frontsteal::noise
