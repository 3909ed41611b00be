// cost_trace.hpp — per-surface tessellation costs along a camera path: what the simulator replays.
//
// A trace holds, for every frame of the path and every surface, the time one core took to tessellate that
// surface for that frame's view (serial loop, mean of a few passes), plus what a static partition needs to
// be recomputed without the scene: each surface's centre and its cost estimate for the first view. Recording
// is in workload.hpp; this file is only the data and its text format:
//
//   frontsteal-cost-trace 1
//   scene plant:15906            (one "key value" line each: scene, path, surfaces, frames, width, height,
//   ...                           tolerance_px, passes, machine, commit)
//   surface <id> <cx> <cy> <cz> <estimate>     (one line per surface)
//   frame <f> <cost_ns of surface 0> <cost_ns of surface 1> ...   (one line per frame)
//
// read_cost_trace throws TraceError naming the file and the line of the first problem.
#pragma once

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace frontsteal::papers {

class TraceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CostTrace {
  std::string scene;
  std::string path = "orbit_then_zoom";
  int width = 1280, height = 720;
  double tolerance_px = 1;
  int passes = 1;  // serial passes the per-surface means come from
  std::string machine, commit;
  std::vector<std::array<double, 3>> centres;  // per surface
  std::vector<double> estimates;               // per surface: cost estimate for frame 0 (static partitions)
  std::vector<std::vector<double>> cost_ns;    // [frame][surface], measured on one core

  std::size_t surfaces() const noexcept { return centres.size(); }
  std::size_t frames() const noexcept { return cost_ns.size(); }
  double frame_cost_ns(std::size_t f) const;  // Σ over surfaces: the serial frame time, bookkeeping excluded
  double path_cost_ns() const;
};

void write_cost_trace(const CostTrace& trace, const std::filesystem::path& file);
CostTrace read_cost_trace(const std::filesystem::path& file);

}  // namespace frontsteal::papers
