// triangle_budget.hpp — a cap on a frame's triangle count: when the plans of a frame would emit more than
// `max_triangles`, the surfaces farthest from the eye are coarsened first.
//
// Why: CAD viewers zoom from a whole assembly to one fillet. With a fixed pixel tolerance the triangle count
// follows the zoom; a budget keeps the frame time bounded, and the far surfaces, which cover the fewest pixels,
// pay first.
//
// Prediction, per surface plan (culled: 0):
//   untrimmed   2 · n_u · n_v, exactly what tessellate_untrimmed emits.
//   trimmed     2 · n_u · n_v · A + T + C, an estimate: A is the trimmed region's share of the unit (u, v)
//               square (shoelace over the loops' control polygons: exact for polyline trims, the control
//               polygon's area for Bézier trims), T the trim points at this plan's ε (trim_segment_steps), and
//               C the grid lines the loops cross (Σ over control-polygon edges of |Δu|·n_u + |Δv|·n_v, leaving
//               out edges along the domain's boundary, which run on grid lines). Full
//               cells give 2 triangles each (≈ 2·n_u·n_v·A); a partial cell's polygon gets one vertex per trim
//               point and per crossing, and an ear-clipped polygon of k vertices gives k − 2 triangles, so the
//               boundary adds about T + C.
// Coarsening: the visible surfaces are sorted by distance from the eye to their control box (0 when the eye
// is inside), farthest first, ties by index: O(n log n), deterministic. Then in passes, each pass walks that
// order and halves one surface's steps at a time (n ↦ max(1, ⌊n/2⌋) in u and in v), until the predicted total
// is within the budget. A surface already at 1 × 1 is passed over; a pass that coarsens nothing ends the
// search (the budget cannot be met: `met` is false, every visible surface is at 1 × 1). There are at most
// ⌈log₂ max_steps⌉ + 1 passes, so the whole is O(n log n + n · log max_steps · trim segments per surface).
// Consequence, which the tests check: the number of halvings a surface got never increases with its distance
// rank, except that a surface held at 1 × 1 stops early.
// A coarsened plan stays consistent: its ε is multiplied by r² and its edge length by r, r the larger of the
// two step ratios (the deviation bound scales with δ², step_sizes.hpp), so the trim polylines (Wang's n_t ∝
// 1/√ε) coarsen with the grid. Coarser steps are still exact tilings: the per-surface audit holds at any step
// counts.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/camera.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::tess {

// The order surfaces are coarsened in. `nearest_first` exists only as the tests' negative control: it must
// break the farthest-first property they check.
enum class CoarseningOrder : std::uint8_t { farthest_first, nearest_first };

struct BudgetOutcome {
  std::uint64_t predicted_before = 0;  // predicted triangles of the plans as given
  std::uint64_t predicted_after = 0;   // ... after coarsening
  std::size_t coarsened = 0;           // surfaces whose steps were reduced
  bool met = true;                     // predicted_after <= max_triangles
};

// The predicted triangle count of one surface plan (see the opening comment).
inline std::uint64_t predict_triangles(const PreparedSurface& s, const SurfacePlan& plan,
                                       const TessellationSettings& settings) {
  if (plan.culled != Culled::no) return 0;
  const double nu = plan.steps.n_u, nv = plan.steps.n_v;
  const double grid = 2.0 * nu * nv;
  if (!s.trimmed()) return static_cast<std::uint64_t>(grid);
  // Shoelace area and grid-line crossings over the loops' control polygons; trim points at this plan's ε.
  double area2 = 0, crossings = 0, trim_points = 0;
  const TrimSegmentShape* shape = s.segment_shapes.data();
  for (const TrimLoop* loop : s.loops) {
    for (const TrimSegment& seg : loop->segments) {
      trim_points += trim_segment_steps(*shape++, s.bounds, plan.epsilon, plan.edge_length, settings.max_trim_steps);
      for (std::size_t k = 0; k + 1 < seg.control.size(); ++k) {
        const glm::dvec2 p = seg.control[k], q = seg.control[k + 1];
        area2 += p.x * q.y - q.x * p.y;
        // An edge along the domain's boundary runs on grid lines: its cells are full, it adds no vertices.
        const bool on_boundary =
            (p.x == q.x && (p.x == 0.0 || p.x == 1.0)) || (p.y == q.y && (p.y == 0.0 || p.y == 1.0));
        if (!on_boundary) crossings += std::abs(q.x - p.x) * nu + std::abs(q.y - p.y) * nv;
      }
    }
  }
  const double share = std::clamp(0.5 * area2, 0.0, 1.0);
  return static_cast<std::uint64_t>(std::llround(grid * share + trim_points + crossings));
}

namespace detail {

// Distance from `eye` to the nearest point of `box` (0 inside).
inline double distance_to_box(const Box& box, const glm::dvec3& eye) {
  const glm::dvec3 nearest = glm::clamp(eye, box.lo, box.hi);
  return glm::length(eye - nearest);
}

// One halving of a plan's steps, with ε and the edge length scaled to stay honest bounds for the new steps.
inline void halve(SurfacePlan& plan) {
  const StepSizes old = plan.steps;
  plan.steps = {std::max(1, old.n_u / 2), std::max(1, old.n_v / 2)};
  const double r =
      std::max(static_cast<double>(old.n_u) / plan.steps.n_u, static_cast<double>(old.n_v) / plan.steps.n_v);
  plan.epsilon *= r * r;
  plan.edge_length *= r;
}

}  // namespace detail

// Coarsens `plans` (one per surface, same order as `surfaces`) until their predicted triangle count is at
// most `max_triangles`, farthest surfaces first. Plans under budget are left exactly as they are.
inline BudgetOutcome apply_triangle_budget(std::span<const PreparedSurface> surfaces, std::span<SurfacePlan> plans,
                                           const Camera& camera, const TessellationSettings& settings,
                                           std::uint64_t max_triangles,
                                           CoarseningOrder order = CoarseningOrder::farthest_first) {
  BudgetOutcome out;
  std::vector<std::uint64_t> predicted(plans.size());
  std::vector<std::size_t> visible;
  for (std::size_t k = 0; k < plans.size(); ++k) {
    predicted[k] = predict_triangles(surfaces[k], plans[k], settings);
    out.predicted_before += predicted[k];
    if (plans[k].culled == Culled::no) visible.push_back(k);
  }
  out.predicted_after = out.predicted_before;
  if (out.predicted_before <= max_triangles) return out;

  // Farthest first (or, as a negative control, nearest first); ties by index, so the order is deterministic.
  std::vector<double> distance(plans.size(), 0.0);
  for (const std::size_t k : visible) distance[k] = detail::distance_to_box(surfaces[k].box, camera.eye);
  std::sort(visible.begin(), visible.end(), [&](std::size_t a, std::size_t b) {
    if (distance[a] != distance[b]) {
      return order == CoarseningOrder::farthest_first ? distance[a] > distance[b] : distance[a] < distance[b];
    }
    return a < b;
  });

  // Passes along that order, one halving per surface and pass, until the prediction fits.
  std::vector<char> touched(plans.size(), 0);
  std::uint64_t total = out.predicted_before;
  bool progress = true;
  while (total > max_triangles && progress) {
    progress = false;
    for (const std::size_t k : visible) {
      if (total <= max_triangles) break;
      if (plans[k].steps == StepSizes{1, 1}) continue;
      detail::halve(plans[k]);
      const std::uint64_t now = predict_triangles(surfaces[k], plans[k], settings);
      total = total - predicted[k] + now;
      predicted[k] = now;
      touched[k] = 1;
      progress = true;
    }
  }
  out.predicted_after = total;
  out.coarsened = static_cast<std::size_t>(std::count(touched.begin(), touched.end(), 1));
  out.met = total <= max_triangles;
  return out;
}

}  // namespace frontsteal::tess
