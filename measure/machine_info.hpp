// machine_info.hpp — small helpers every results writer shares: the CPU model and hardware thread count for
// the stamp on measured figures, and the median the tables report.
#pragma once

#include <algorithm>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace frontsteal {

// The "model name" of /proc/cpuinfo, or "unknown CPU".
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  }
  return "unknown CPU";
}

// The hardware threads this process may run on, at least 1 (std::thread::hardware_concurrency() may say 0).
inline unsigned hardware_cores() { return std::max(1u, std::thread::hardware_concurrency()); }

// "<cpu model>, N hardware threads": the machine a measured figure was made on, as results files name it.
inline std::string machine_description() {
  return cpu_model() + ", " + std::to_string(hardware_cores()) + " hardware threads";
}

// The 1-minute load average from /proc/loadavg, as written there, or "unknown": results files say how busy
// the machine was while they were measured.
inline std::string load_average_1min() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one.empty() ? "unknown" : one;
}

// The median of v (0 for an empty v); the mean of the two middle values for an even count.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

}  // namespace frontsteal
