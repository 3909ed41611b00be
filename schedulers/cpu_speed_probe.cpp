// cpu_speed_probe.cpp — the probe and the spread diagnosis (cpu_speed_probe.hpp).
#include "schedulers/cpu_speed_probe.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "schedulers/noise_monitor.hpp"

namespace frontsteal::noise {

namespace {

std::string pct(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100 * share);
  return buf;
}

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

double probe_ns_per_mstep(std::uint64_t steps) {
  if (steps == 0) steps = 1;
  // Four independent chains, so that the multiplier and the ALUs are kept busy (throughput-bound): a busy SMT
  // sibling on the host's core competes for exactly those, and a lone latency-bound chain would barely notice.
  std::uint64_t a = 0x9e3779b97f4a7c15ull, b = 0xbf58476d1ce4e5b9ull, c = 0x94d049bb133111ebull, d = 0x2545f4914f6cdd1dull;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < steps; ++i) {
    a = a * 6364136223846793005ull + 1442695040888963407ull;
    b = b * 6364136223846793005ull + 1442695040888963407ull;
    c = c * 6364136223846793005ull + 1442695040888963407ull;
    d = d * 6364136223846793005ull + 1442695040888963407ull;
    a ^= a >> 29;
    b ^= b >> 29;
    c ^= c >> 29;
    d ^= d >> 29;
  }
  const auto t1 = std::chrono::steady_clock::now();
  // Keep the chains: without a use of their values the compiler may drop the loop.
  const std::uint64_t all = a ^ b ^ c ^ d;
  asm volatile("" : : "r"(all) : "memory");
  return std::chrono::duration<double, std::nano>(t1 - t0).count() * 1e6 / static_cast<double>(steps);
}

SpreadDiagnosis diagnose_spread(const std::vector<double>& serial_ms, const std::vector<double>& probe, double threshold,
                                const std::vector<PassUsage>& passes) {
  SpreadDiagnosis d;
  d.serial_spread = spread_of(serial_ms);
  if (probe.size() != serial_ms.size() || probe.empty()) {
    d.line = "CPU speed probe: not measured";
    return d;
  }
  d.probe_spread = spread_of(probe);
  d.correlation = probe.size() >= 3 ? pearson(serial_ms, probe) : 0.0;
  d.cpu_varied = d.probe_spread > threshold;
  d.user_mode_only = passes.size() == serial_ms.size() && user_mode_only(passes);
  char r[32];
  std::snprintf(r, sizeof r, "%.2f", d.correlation);
  const std::string probe_says = "a fixed arithmetic loop timed beside each serial pass spread " + pct(d.probe_spread) +
                                 " (correlation with the passes r = " + r + ")";
  std::string work_says;  // what the passes' own threads did, when measured
  if (passes.size() == serial_ms.size() && !passes.empty()) {
    long faults = 0, blocked = 0, preempted = 0;
    double system_ms = 0;
    for (const PassUsage& p : passes) {
      faults += p.faults;
      blocked += p.voluntary_switches;
      preempted = std::max(preempted, p.involuntary_switches);
      system_ms += p.system_ms;
    }
    char buf[200];
    std::snprintf(buf, sizeof buf, "%ld page faults, %.0f ms system time, %ld blocking waits in all passes; at most %ld "
                  "involuntary switches in one", faults, system_ms, blocked, preempted);
    work_says = buf;
  }
  if (d.serial_spread <= threshold) {
    d.line = "CPU speed probe: " + probe_says;
  } else if (d.cpu_varied && d.probe_spread >= 0.5 * d.serial_spread) {
    d.machine = true;
    d.line = "the CPU itself changed speed between repeats: " + probe_says +
             ", most of the serial loop's " + pct(d.serial_spread) +
             "; /proc cannot see this (a lower host clock or a busy SMT sibling on the host): the machine, not the program";
  } else if (d.user_mode_only) {
    d.machine = true;
    d.line = "every serial pass did the same work in user mode (" + work_says + ") and still spread " +
             pct(d.serial_spread) + ": the same instructions ran slower, so the hardware or its state, not the "
             "program's work — " + probe_says + "; the rest is what an arithmetic loop does not feel (caches or "
             "memory shared with other tenants, or caches left cold by the run before)";
  } else if (d.cpu_varied) {
    d.line = "the CPU's speed changed between repeats, but less than the serial loop's time: " + probe_says +
             " against the passes' " + pct(d.serial_spread) +
             "; the rest is memory, caches, the program, or a slowdown the arithmetic probe does not feel" +
             (work_says.empty() ? "" : " (" + work_says + ")");
  } else {
    d.line = "the CPU's speed did not change between repeats (" + probe_says +
             "): the serial loop's own time varied — memory, caches or the program, not the core's clock" +
             (work_says.empty() ? "" : " (" + work_says + ")");
  }
  return d;
}

}  // namespace frontsteal::noise
