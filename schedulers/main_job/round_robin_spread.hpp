// round_robin_spread.hpp — how unbalanced round robin is on a camera path: per frame, the items' costs dealt
// as the round-robin scheduler deals them (item i to worker i mod P, static_assignment.hpp), and the ratio
// max / min of the workers' sums. The paper (§3) cites 1:50 for static schemes on its walkthroughs; this is
// the number the main job prints per path (from measured per-item times, from cost estimates, and from the
// round-robin row's busy time), and the one the tests check grows on the paths built to unbalance it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace frontsteal::sched {

struct CostSpread {
  std::vector<double> per_frame;  // max / min over workers (infinity when a worker's sum is 0)
  double worst = 0;               // the largest per-frame ratio
  int worst_frame = -1;
  double median = 0;  // of the per-frame ratios
};

// The per-frame ratios of given per-frame ratios (summary only).
inline CostSpread summarize_spread(std::vector<double> per_frame) {
  CostSpread s;
  s.per_frame = std::move(per_frame);
  for (std::size_t f = 0; f < s.per_frame.size(); ++f) {
    if (s.worst_frame < 0 || s.per_frame[f] > s.worst) {
      s.worst = s.per_frame[f];
      s.worst_frame = static_cast<int>(f);
    }
  }
  if (!s.per_frame.empty()) {
    std::vector<double> v = s.per_frame;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    s.median = v[v.size() / 2];
    if (v.size() % 2 == 0) {
      s.median = 0.5 * (s.median + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2)));
    }
  }
  return s;
}

// max / min of per-worker loads; infinity when the least loaded has nothing, 1 for one worker.
inline double load_ratio(const std::vector<double>& loads) {
  if (loads.size() < 2) return 1.0;
  const auto [lo, hi] = std::minmax_element(loads.begin(), loads.end());
  return *lo > 0 ? *hi / *lo : std::numeric_limits<double>::infinity();
}

// costs[f][i]: item i's cost in frame f (any unit). Dealt round robin to `workers`.
inline CostSpread round_robin_spread(const std::vector<std::vector<double>>& costs, std::size_t workers) {
  std::vector<double> ratios;
  for (const auto& frame : costs) {
    std::vector<double> load(std::max<std::size_t>(1, workers), 0.0);
    for (std::size_t i = 0; i < frame.size(); ++i) load[i % load.size()] += frame[i];
    ratios.push_back(load_ratio(load));
  }
  return summarize_spread(std::move(ratios));
}

// A ratio for a report: two decimals, "inf" for a worker with nothing.
inline std::string ratio_text(double v) {
  if (std::isinf(v)) return "inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// {"worst": …, "worst_frame": …, "median": …, "per_frame": […]}; infinity is written as null.
inline std::string to_json(const CostSpread& c) {
  auto number = [](double v) {
    if (std::isinf(v)) return std::string("null");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", v);
    return std::string(buf);
  };
  std::string j = "{\"worst\": " + number(c.worst) + ", \"worst_frame\": " + std::to_string(c.worst_frame) +
                  ", \"median\": " + number(c.median) + ", \"per_frame\": [";
  for (std::size_t f = 0; f < c.per_frame.size(); ++f) j += (f ? ", " : "") + number(c.per_frame[f]);
  return j + "]}";
}

}  // namespace frontsteal::sched
