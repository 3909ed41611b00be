// cpu_speed_probe.cpp — the probe and the spread diagnosis (cpu_speed_probe.hpp).
#include "schedulers/cpu_speed_probe.hpp"

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
  std::uint64_t x = 0x9e3779b97f4a7c15ull;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < steps; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;  // each step needs the last: no overlap
    x ^= x >> 29;
    x ^= x << 17;
  }
  const auto t1 = std::chrono::steady_clock::now();
  // Keep the chain: without a use of x the compiler may drop the loop.
  asm volatile("" : : "r"(x) : "memory");
  return std::chrono::duration<double, std::nano>(t1 - t0).count() * 1e6 / static_cast<double>(steps);
}

SpreadDiagnosis diagnose_spread(const std::vector<double>& serial_ms, const std::vector<double>& probe, double threshold) {
  SpreadDiagnosis d;
  d.serial_spread = spread_of(serial_ms);
  if (probe.size() != serial_ms.size() || probe.empty()) {
    d.line = "CPU speed probe: not measured";
    return d;
  }
  d.probe_spread = spread_of(probe);
  d.correlation = probe.size() >= 3 ? pearson(serial_ms, probe) : 0.0;
  d.cpu_varied = d.probe_spread > threshold;
  char r[32];
  std::snprintf(r, sizeof r, "%.2f", d.correlation);
  const std::string probe_says = "a fixed arithmetic loop timed beside each serial pass spread " + pct(d.probe_spread) +
                                 " (correlation with the passes r = " + r + ")";
  if (d.serial_spread <= threshold) {
    d.line = "CPU speed probe: " + probe_says;
  } else if (d.cpu_varied) {
    d.line = "the CPU itself changed speed between repeats: " + probe_says +
             "; /proc cannot see this (a lower host clock or a busy SMT sibling on the host): the machine, not the program";
  } else {
    d.line = "the CPU's speed did not change between repeats (" + probe_says +
             "): the serial loop's own time varied — memory, caches or the program, not the core's clock";
  }
  return d;
}

}  // namespace frontsteal::noise
