// phase_profile.hpp — where a frame's tessellation time goes, phase by phase, measured inside the tessellator.
//
// A worker's TessellationScratch may point at a PhaseProfile; the tessellator then marks the end of each phase
// (PhaseLap::to) and the time since the previous mark is added to that phase, read from the steady clock. With
// no profile (the product's default) a mark is one predictable branch and reads no clock. With one, each mark
// costs a clock read (~20-40 ns on these VMs), so a profiled frame runs slower than a plain one; frame_benchmark
// reports both, so the profile's own cost is visible, and perf's independent sampling profile
// (results/tessellate/frame-profile/) cross-checks the split.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace frontsteal::tess {

enum class Phase : std::uint8_t {
  cull,            // plan_surface for a surface that ends culled
  plan,            // plan_surface for a visible one: tolerances and step sizes
  untrimmed_grid,  // an untrimmed surface's grid: evaluation, normals, indices
  trim_polylines,  // trim curves to this frame's polylines, and their enclosed area (the audit's reference)
  trace,           // the region tracer: trim polylines cut by the grid, pieces of partial cells
  trimmed_cells,   // trimmed surfaces' vertices (evaluated once each) and full cells' triangles
  triangulate,     // partial cells' pieces: holes joined, ears clipped
  audit,           // each piece's tiling check and its containment in its cell
};
inline constexpr std::size_t kPhaseCount = 8;

inline const char* to_string(Phase p) noexcept {
  constexpr const char* kNames[kPhaseCount] = {"cull",  "plan",          "untrimmed grid", "trim polylines",
                                               "trace", "trimmed cells", "triangulate",    "audit"};
  return kNames[static_cast<std::size_t>(p)];
}

struct PhaseProfile {
  std::array<double, kPhaseCount> seconds{};
  std::array<std::uint64_t, kPhaseCount> marks{};
  void clear() noexcept { *this = PhaseProfile{}; }
  double total() const noexcept {
    double t = 0;
    for (double s : seconds) t += s;
    return t;
  }
};

// Marks phase boundaries for one surface. Construct where the first phase starts.
class PhaseLap {
 public:
  using Clock = std::chrono::steady_clock;
  explicit PhaseLap(PhaseProfile* profile) noexcept : profile_(profile) {
    if (profile_ != nullptr) [[unlikely]]
      last_ = Clock::now();
  }
  // The time since the previous mark (or construction) belongs to `phase`.
  void to(Phase phase) noexcept {
    if (profile_ == nullptr) [[likely]]
      return;
    const Clock::time_point now = Clock::now();
    const auto k = static_cast<std::size_t>(phase);
    profile_->seconds[k] += std::chrono::duration<double>(now - last_).count();
    ++profile_->marks[k];
    last_ = now;
  }

 private:
  PhaseProfile* profile_;
  Clock::time_point last_{};
};

}  // namespace frontsteal::tess
