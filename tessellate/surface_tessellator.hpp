// surface_tessellator.hpp — one trimmed surface, one camera: cull, choose step sizes, triangulate.
//
// Per frame and surface (paper §2):
//   1. Culling (culling.hpp): the control box against the frustum; solids' back faces by the cone of normals.
//   2. Object-space tolerances from pixels. A displacement Δ at view depth z moves the image by at most
//      (f_px / z)·√(1 + (x/z)² + (y/z)²)·‖Δ‖ pixels (the Jacobian of x ↦ f x/z has that largest singular value),
//      and inside the frustum |x/z| ≤ tan(fovx/2), |y/z| ≤ tan(fovy/2). With d_min the nearest depth of the
//      control box (at least the near plane), every point of the patch and of its triangles is at depth ≥ d_min,
//      so ε_obj = ε_px · d_min / (f_px · k), k = √(1 + tan²(fovx/2) + tan²(fovy/2)), keeps the screen deviation
//      within ε_px (the plain ε_px·d_min/f_px of the literature ignores k, up to 1.5 at the image corners).
//      The same stretch is (f_px / z)·|p| / z with |p| the distance from the eye, so over the control box
//      (|p| ≤ r_max, the farthest corner; z ≥ d_min) k may be r_max / d_min instead where that is smaller: a
//      small patch near the view axis gets k ≈ 1, not the image corner's factor.
//      The same conversion turns the size bound (edges ≤ max_edge_pixels) into an object length.
//   3. Step sizes n_u, n_v (step_sizes.hpp): the larger of the deviation bound (Filip et al.) and the size
//      bound, clamped to max_steps. The deviation bound holds for every triangle whose vertices lie in one grid
//      cell (the variance of a distribution on [u₀,u₁] is at most δu²/4), so it covers trimmed cells too.
//   4. Trim curves to polylines: n_t per Bézier trim segment c of degree d ≥ 2 from Wang's formula in the
//      domain, n_t = ⌈√(d(d−1)·max‖Δ²c‖ / (8 ε_dom))⌉ with ε_dom = ε_obj / (M_u + M_v) (M_u, M_v bound ‖S_u‖,
//      ‖S_v‖, so a domain error δ moves the surface by at most (M_u + M_v)·‖δ‖∞), and at least the size bound
//      d·(M_u max|Δu_k| + M_v max|Δv_k|) / ℓ_obj; degree-1 segments stay single segments (the grid lines they
//      cross add the vertices the surface needs).
//   5. Untrimmed: the uniform grid (grid_tessellator.hpp). Trimmed: the grid cut by the trim polylines
//      (trim_region.hpp); full cells give two triangles split by the diagonal, partial cells are ear-clipped
//      (polygon_triangulation.hpp), except large pieces (a long trim polyline in one cell), which get a
//      constrained triangulation (constrained_triangulation.hpp: ear clipping is quadratic). Grid corners and trim
//      points each become one vertex, shared by every triangle that uses them, so there are no cracks inside a patch.
//   6. Every trimmed surface audits itself (SurfaceResult): each piece's triangles must tile the piece exactly
//      (tiling_audit.hpp: no overlap, no covered hole, no gap), every piece must lie in its cell (so pieces of
//      different cells cannot overlap), and the triangles' (u, v) area must equal the area enclosed by this
//      frame's trim polylines, computed from the polylines alone by the shoelace formula (independent of the
//      region tracer). Violations are counted as inconsistencies; callers fail on any.
// A pure function of (surface, camera, settings): it can run on any worker, in any order, and twice without
// harm. Buffers and scratch keep their capacity across frames: no allocation in steady state.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/camera.hpp"
#include "tessellate/constrained_triangulation.hpp"
#include "tessellate/culling.hpp"
#include "tessellate/grid_tessellator.hpp"
#include "tessellate/model.hpp"
#include "tessellate/phase_profile.hpp"
#include "tessellate/polygon_triangulation.hpp"
#include "tessellate/step_sizes.hpp"
#include "tessellate/tiling_audit.hpp"
#include "tessellate/trim_region.hpp"

namespace frontsteal::tess {

// Negative controls only: a known triangulation defect that tests plant to show the per-surface audit (step 6)
// catches it. `bridge_to_first_copy` is the wave-1 defect (polygon_triangulation.hpp, step 1); `drop_ear`
// leaves out the first triangle of every piece with more than one.
enum class PlantedDefect : std::uint8_t { none, bridge_to_first_copy, drop_ear };

// The names the command lines use: wave1-bridge, drop-ear.
inline std::optional<PlantedDefect> planted_defect_named(std::string_view name) {
  if (name == "wave1-bridge") return PlantedDefect::bridge_to_first_copy;
  if (name == "drop-ear") return PlantedDefect::drop_ear;
  return std::nullopt;
}

struct TessellationSettings {
  double pixel_tolerance = 1.0;   // largest screen-space deviation of the triangles from the surface, pixels
  double max_edge_pixels = 48.0;  // size bound: grid edges no longer than this on screen, pixels
  int max_steps = 256;            // per direction and patch
  int max_trim_steps = 128;       // per trim segment
  bool frustum_culling = true;
  bool back_face_culling = true;                       // solids only
  PlantedDefect planted_defect = PlantedDefect::none;  // tests only
  bool single_precision = true;  // grid corners in float where the error bound allows (grid_row_kernel.hpp)
};

enum class Culled : std::uint8_t { no, frustum, back_face };

// What n_t of a trim segment (step 4) needs of its control polygon: independent of the view, so computed once.
struct TrimSegmentShape {
  int degree = 1;
  double second = 0;      // max ‖c_{k+2} − 2c_{k+1} + c_k‖
  double du = 0, dv = 0;  // max |Δu_k|, max |Δv_k|
};

inline TrimSegmentShape trim_segment_shape(const TrimSegment& seg) {
  TrimSegmentShape shape;
  const int d = shape.degree = seg.degree();
  if (d <= 1) return shape;
  for (int k = 0; k + 1 <= d; ++k) {
    shape.du = std::max(shape.du, std::abs(seg.control[k + 1].x - seg.control[k].x));
    shape.dv = std::max(shape.dv, std::abs(seg.control[k + 1].y - seg.control[k].y));
    if (k + 2 <= d)
      shape.second =
          std::max(shape.second, glm::length(seg.control[k + 2] - 2.0 * seg.control[k + 1] + seg.control[k]));
  }
  return shape;
}

// What a surface needs every frame that does not depend on the view.
struct PreparedSurface {
  const Surface* surface = nullptr;
  NetBounds bounds;
  Box box;
  double radius = 0;  // of the control points around box.centre()
  NormalCone cone;
  double float_error = 0;              // float_row_error_bound: the single-precision grid's position error bound
  std::vector<const TrimLoop*> loops;  // trim loops; empty when untrimmed or trimmed by the domain alone
  std::vector<TrimSegmentShape> segment_shapes;  // of every segment of `loops`, loop by loop
  bool trimmed() const noexcept { return !loops.empty(); }
};

namespace detail {

inline bool is_domain_boundary(const TrimLoop& loop) {
  for (const TrimSegment& seg : loop.segments) {
    if (seg.degree() != 1) return false;
    for (const glm::dvec2& p : seg.control) {
      const bool on = p.x == 0.0 || p.x == 1.0 || p.y == 0.0 || p.y == 1.0;
      if (!on) return false;
    }
  }
  return std::abs(0.5 * signed_area2(sample_loop(loop)) - 1.0) < 1e-12;
}

}  // namespace detail

inline PreparedSurface prepare_surface(const Surface& s) {
  PreparedSurface p;
  p.surface = &s;
  p.bounds = net_bounds(s.patch);
  p.box = control_box(s.patch);
  const glm::dvec3 c = p.box.centre();
  for (int i = 0; i <= s.patch.degree_u; ++i) {
    for (int j = 0; j <= s.patch.degree_v; ++j) p.radius = std::max(p.radius, glm::length(s.patch.point(i, j) - c));
  }
  if (s.solid) p.cone = normal_cone(s.patch);
  p.float_error = float_row_error_bound(s.patch);
  // A lone outer loop along the domain's boundary trims nothing; with holes, the region tracer needs it (it
  // counts such a loop as winding +1 everywhere rather than walking it).
  const bool only_domain = s.loops.size() == 1 && detail::is_domain_boundary(s.loops[0]);
  if (!only_domain) {
    for (const TrimLoop& loop : s.loops) p.loops.push_back(&loop);
  }
  for (const TrimLoop* loop : p.loops) {
    for (const TrimSegment& seg : loop->segments) p.segment_shapes.push_back(trim_segment_shape(seg));
  }
  return p;
}

// The view-dependent plan for one surface: culled or not, tolerances, step sizes.
struct SurfacePlan {
  Culled culled = Culled::no;
  double epsilon = 0;      // object-space deviation tolerance
  double edge_length = 0;  // object-space size bound
  StepSizes steps;
  // The deviation bound wanted more than max_steps in a direction: the cap holds, so the screen deviation of
  // this surface may exceed the pixel tolerance. Reported per frame, never silent.
  bool capped = false;
  // The grid's corners (untrimmed grids, and the corners of trimmed ones) may be evaluated in single precision:
  // the float kernel's error bound is within a tenth of epsilon. Trim points are evaluated in double always.
  bool single_precision = false;
};

// Whether the grid's corners of `s` may be evaluated in single precision at object-space tolerance `epsilon`.
inline bool single_precision_allowed(const PreparedSurface& s, double epsilon, const TessellationSettings& settings) {
  return settings.single_precision && s.float_error <= 0.1 * epsilon;
}

inline SurfacePlan plan_surface(const PreparedSurface& s, const Camera& camera, const Frustum& frustum,
                                const TessellationSettings& settings) {
  SurfacePlan plan;
  if (settings.frustum_culling && outside_frustum(s.box, frustum)) {
    plan.culled = Culled::frustum;
    return plan;
  }
  if (settings.back_face_culling && s.surface->solid && faces_away(s.cone, s.box.centre(), s.radius, camera.eye)) {
    plan.culled = Culled::back_face;
    return plan;
  }
  const glm::dvec3 forward = camera.forward();
  double d_min = std::numeric_limits<double>::infinity(), r2_max = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c = s.box.corner(k) - camera.eye;
    d_min = std::min(d_min, glm::dot(c, forward));
    r2_max = std::max(r2_max, glm::dot(c, c));
  }
  const double r_max = std::sqrt(r2_max);  // the largest length: sqrt is monotonic and correctly rounded
  d_min = std::max(d_min, camera.near_plane);
  const double tx = camera.tan_half_fovx(), ty = camera.tan_half_fovy();
  // The perspective factor k of step 2: the smaller of the frustum's and the box's own (|p| / z ≤ r_max / d_min).
  const double k = std::clamp(r_max / d_min, 1.0, std::sqrt(1.0 + tx * tx + ty * ty));
  const double object_per_pixel = d_min / (camera.focal_pixels() * k);
  plan.epsilon = settings.pixel_tolerance * object_per_pixel;
  plan.edge_length = settings.max_edge_pixels * object_per_pixel;
  const StepSizes d = deviation_steps(s.bounds, plan.epsilon, settings.max_steps + 1);
  plan.capped = d.n_u > settings.max_steps || d.n_v > settings.max_steps;
  const StepSizes z = size_steps(s.bounds, plan.edge_length, settings.max_steps);
  plan.steps = {std::min(std::max(d.n_u, z.n_u), settings.max_steps),
                std::min(std::max(d.n_v, z.n_v), settings.max_steps)};
  plan.single_precision = single_precision_allowed(s, plan.epsilon, settings);
  return plan;
}

// n_t for one trim segment (step 4 of the opening comment), from its shape (PreparedSurface::segment_shapes).
inline int trim_segment_steps(const TrimSegmentShape& shape, const NetBounds& b, double epsilon, double edge_length,
                              int max_steps) {
  const int d = shape.degree;
  if (d <= 1) return 1;
  const double eps_domain = epsilon / std::max(b.len_u + b.len_v, 1e-300);
  const double wang = std::ceil(std::sqrt(d * (d - 1) * shape.second / (8.0 * eps_domain)));
  const double size = std::ceil(d * (b.len_u * shape.du + b.len_v * shape.dv) / edge_length);
  return static_cast<int>(std::clamp(std::max(wang, size), 1.0, static_cast<double>(max_steps)));
}
inline int trim_segment_steps(const TrimSegment& seg, const NetBounds& b, double epsilon, double edge_length,
                              int max_steps) {
  return trim_segment_steps(trim_segment_shape(seg), b, epsilon, edge_length, max_steps);
}

// A per-surface cost estimate in "basis-weighted vertex evaluations", for static allocation: the grid's
// vertices times the patch's (m+1)(n+1) control points, plus trimmed work (trim points and the partial cells
// they cut, each about a vertex evaluation and an ear clip). Culled surfaces cost a little (the tests).
inline double estimate_cost(const PreparedSurface& s, const SurfacePlan& plan, const TessellationSettings& settings) {
  constexpr double kCullCost = 10.0;
  if (plan.culled != Culled::no) return kCullCost;
  const double per_vertex = (s.surface->patch.degree_u + 1.0) * (s.surface->patch.degree_v + 1.0);
  const double grid = (plan.steps.n_u + 1.0) * (plan.steps.n_v + 1.0);
  double trim_points = 0;
  for (const TrimSegmentShape& shape : s.segment_shapes) {
    trim_points += trim_segment_steps(shape, s.bounds, plan.epsilon, plan.edge_length, settings.max_trim_steps);
  }
  // A trim polyline of t points cuts about t + crossings cells; each costs a few evaluations.
  const double trimmed_work = trim_points * 4.0 * per_vertex;
  return kCullCost + grid * per_vertex + trimmed_work;
}

struct SurfaceResult {
  Culled culled = Culled::no;
  StepSizes steps;
  bool capped = false;  // SurfacePlan::capped
  std::uint32_t triangles = 0;
  std::uint32_t trim_points = 0;
  std::uint32_t partial_cells = 0;
  std::uint32_t constrained_pieces = 0;  // pieces triangulated by constrained_triangulation.hpp, not ear clipping
  std::uint32_t trace_failures = 0;      // trim input the region tracer could not place (crossing loops)
  std::uint32_t tiling_violations = 0;   // pieces not tiled exactly by their triangles, or outside their cell
  std::uint32_t area_mismatches = 0;     // 1 when the triangles' (u, v) area is not the trim polylines' area
  double triangle_area = 0;              // (u, v) area of the emitted triangles (trimmed surfaces)
  double trimmed_area = 0;               // (u, v) area enclosed by this frame's trim polylines (shoelace)
  // Everything the per-surface audit (step 6) found wrong: 0 for a correct tessellation.
  std::uint32_t inconsistencies() const noexcept { return trace_failures + tiling_violations + area_mismatches; }
};

// Per-worker scratch: everything a surface's tessellation needs, reused across surfaces and frames.
struct TessellationScratch {
  // The trimmed path's grid-line tables, kept while consecutive trimmed surfaces share (degree, steps): only
  // tessellate_trimmed writes them (the untrimmed double grid has its own `grid_basis`), so no other use of the
  // scratch can leave them stale.
  std::vector<BernsteinTable> trim_u_basis, trim_v_basis;
  std::pair<int, int> trim_u_basis_for{-1, -1}, trim_v_basis_for{-1, -1};  // (degree, steps) they were made for
  std::vector<BernsteinTable> grid_basis;                                  // tessellate_untrimmed's scratch
  std::vector<double> u_lines, v_lines;
  std::vector<Polygon2> loops;
  GridTrimmer trimmer;
  std::vector<std::uint32_t> corner_vertex, trim_vertex;  // output index or kNone
  PolygonRing ring;
  std::vector<PolygonRing> holes;
  std::vector<std::uint32_t> ring_triangles, next, prev;
  TilingAudit tiling;
  FloatGridScratch float_grid;
  // The trimmed path's grid rows in float (float_grid_row), one per parity of the row index, as `rows` below.
  struct FloatRow {
    std::vector<glm::vec3> position, normal;
    std::vector<std::uint8_t> degenerate;
  };
  FloatRow trim_float_rows[2];
  PhaseProfile* profile = nullptr;  // where the time goes (phase_profile.hpp); none in the product
  static constexpr std::uint32_t kNone = 0xffff'ffffu;
};

namespace detail {

inline glm::dvec2 trim_point(const TrimSegment& seg, double t) {
  glm::dvec2 c[kMaxDegree + 1];
  const int d = seg.degree();
  for (int k = 0; k <= d; ++k) c[k] = seg.control[k];
  for (int r = 1; r <= d; ++r) {
    for (int k = 0; k + r <= d; ++k) c[k] = (1 - t) * c[k] + t * c[k + 1];
  }
  return c[0];
}

}  // namespace detail

// Triangulates the trimmed surface on the plan's grid into `out` (cleared first).
inline SurfaceResult tessellate_trimmed(const PreparedSurface& s, const SurfacePlan& plan,
                                        const TessellationSettings& settings, TessellationScratch& scratch,
                                        TriangleBuffers& out) {
  const BezierPatch& patch = s.surface->patch;
  const int nu = plan.steps.n_u, nv = plan.steps.n_v;
  SurfaceResult result;
  result.steps = plan.steps;
  result.capped = plan.capped;
  PhaseLap lap(scratch.profile);
  out.clear();
  // Trim polylines at this frame's n_t.
  scratch.loops.resize(s.loops.size());
  const TrimSegmentShape* shape = s.segment_shapes.data();
  for (std::size_t l = 0; l < s.loops.size(); ++l) {
    Polygon2& poly = scratch.loops[l];
    poly.clear();
    for (const TrimSegment& seg : s.loops[l]->segments) {
      const int n = trim_segment_steps(*shape++, s.bounds, plan.epsilon, plan.edge_length, settings.max_trim_steps);
      for (int k = 0; k < n; ++k) poly.push_back(detail::trim_point(seg, static_cast<double>(k) / n));
    }
    result.trim_points += static_cast<std::uint32_t>(poly.size());
  }
  scratch.u_lines.resize(static_cast<std::size_t>(nu + 1));
  scratch.v_lines.resize(static_cast<std::size_t>(nv + 1));
  // The audit's reference area: the polylines the tracer gets, clamped to the domain as it clamps them.
  double perimeter = 0;
  for (const Polygon2& poly : scratch.loops) {
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const glm::dvec2 p = glm::clamp(poly[k], 0.0, 1.0), q = glm::clamp(poly[(k + 1) % poly.size()], 0.0, 1.0);
      result.trimmed_area += 0.5 * (p.x * q.y - q.x * p.y);
      perimeter += glm::length(q - p);
    }
  }
  for (int i = 0; i <= nu; ++i) scratch.u_lines[i] = static_cast<double>(i) / nu;
  for (int j = 0; j <= nv; ++j) scratch.v_lines[j] = static_cast<double>(j) / nv;
  scratch.u_lines[nu] = scratch.v_lines[nv] = 1.0;
  lap.to(Phase::trim_polylines);
  GridTrimmer& trimmer = scratch.trimmer;
  trimmer.run(scratch.loops, scratch.u_lines, scratch.v_lines);
  lap.to(Phase::trace);

  // The grid lines' basis tables depend only on (degree, steps); kept while consecutive surfaces share them.
  if (scratch.trim_u_basis_for != std::pair(patch.degree_u, nu)) {
    scratch.trim_u_basis.resize(static_cast<std::size_t>(nu + 1));
    for (int i = 0; i <= nu; ++i) scratch.trim_u_basis[i] = bernstein(patch.degree_u, scratch.u_lines[i]);
    scratch.trim_u_basis_for = {patch.degree_u, nu};
  }
  if (scratch.trim_v_basis_for != std::pair(patch.degree_v, nv)) {
    scratch.trim_v_basis.resize(static_cast<std::size_t>(nv + 1));
    for (int j = 0; j <= nv; ++j) scratch.trim_v_basis[j] = bernstein(patch.degree_v, scratch.v_lines[j]);
    scratch.trim_v_basis_for = {patch.degree_v, nv};
  }
  scratch.corner_vertex.assign(static_cast<std::size_t>((nu + 1) * (nv + 1)), TessellationScratch::kNone);
  scratch.trim_vertex.assign(trimmer.points().size(), TessellationScratch::kNone);

  // Grid corners by rows collapsed once (RowCurve: 3(n+1) terms per vertex instead of 3(m+1)(n+1)); in single
  // precision, whole rows at a time by the SIMD float kernel, as untrimmed grids. Cells are visited row by row
  // and use grid rows i and i+1, which differ in parity: one cached row per parity. A corner becomes an output
  // vertex when a triangle first uses it, in either precision, so the vertex order does not depend on it.
  RowCurve rows[2];
  int cached_row[2] = {-1, -1};
  const auto grid_row = [&](int i) -> const RowCurve& {
    const int slot = i & 1;
    if (cached_row[slot] != i) {
      rows[slot].collapse(patch, scratch.trim_u_basis[i]);
      cached_row[slot] = i;
    }
    return rows[slot];
  };
  if (plan.single_precision) {
    prepare_float_grid(patch.degree_v, nv, scratch.float_grid);
    for (TessellationScratch::FloatRow& row : scratch.trim_float_rows) {
      row.position.resize(static_cast<std::size_t>(nv + 1));
      row.normal.resize(static_cast<std::size_t>(nv + 1));
    }
  }
  const auto float_row = [&](int i) -> const TessellationScratch::FloatRow& {
    const int slot = i & 1;
    TessellationScratch::FloatRow& row = scratch.trim_float_rows[slot];
    if (cached_row[slot] != i) {
      float_grid_row(patch, scratch.trim_u_basis[i], nv, scratch.float_grid, row.position.data(), row.normal.data());
      row.degenerate.assign(scratch.float_grid.degenerate.begin(), scratch.float_grid.degenerate.end());
      cached_row[slot] = i;
    }
    return row;
  };
  // Grid corner (i, j) from its float row, as (position, normal); a collapsed edge's normal from the double evaluator.
  const auto float_corner = [&](int i, int j) {
    const TessellationScratch::FloatRow& row = float_row(i);
    const std::size_t at = static_cast<std::size_t>(j);
    const glm::vec3 normal = row.degenerate[at] != 0
                                 ? glm::vec3(evaluate(patch, scratch.u_lines[i], scratch.v_lines[j]).normal)
                                 : row.normal[at];
    return std::pair(row.position[at], normal);
  };
  // The output vertex of a grid corner or trim point, made on first use. Making one is out of line: the common
  // case, a vertex made already, is then a load and a compare where the cells are visited.
  const auto make_vertex = [&](std::uint32_t id) __attribute__((noinline))->std::uint32_t {
    if (id & GridTrimmer::kCornerBit) {
      const std::uint32_t k = id & ~GridTrimmer::kCornerBit;
      const int i = static_cast<int>(k / static_cast<std::uint32_t>(nv + 1));
      const int j = static_cast<int>(k % static_cast<std::uint32_t>(nv + 1));
      const double u = scratch.u_lines[i], v = scratch.v_lines[j];
      if (plan.single_precision) {
        const auto [position, normal] = float_corner(i, j);
        return scratch.corner_vertex[k] = out.add_vertex(position, normal, u, v);
      }
      SurfacePoint sp = grid_row(i).at(patch.degree_v, scratch.trim_v_basis[j]);
      if (sp.normal == glm::dvec3(0.0)) sp.normal = evaluate(patch, u, v).normal;
      return scratch.corner_vertex[k] = out.add_vertex(sp, u, v);
    }
    const glm::dvec2 uv = trimmer.points()[id];
    if (plan.single_precision) {
      // A trim point exactly on a grid corner (a trim edge passing through it diagonally) is the corner for the
      // cells beside it that use the corner's own vertex: it takes the corner's float position, or the two would
      // sit up to the float error bound apart and open a crack along the cell edge they share.
      const int i = static_cast<int>(std::lround(uv.x * nu)), j = static_cast<int>(std::lround(uv.y * nv));
      if (i >= 0 && i <= nu && j >= 0 && j <= nv && scratch.u_lines[i] == uv.x && scratch.v_lines[j] == uv.y) {
        const auto [position, normal] = float_corner(i, j);
        return scratch.trim_vertex[id] = out.add_vertex(position, normal, uv.x, uv.y);
      }
    }
    return scratch.trim_vertex[id] = out.add_vertex(evaluate(patch, uv.x, uv.y), uv.x, uv.y);
  };
  const auto vertex = [&](std::uint32_t id) -> std::uint32_t {
    const std::uint32_t made =
        id & GridTrimmer::kCornerBit ? scratch.corner_vertex[id & ~GridTrimmer::kCornerBit] : scratch.trim_vertex[id];
    return made != TessellationScratch::kNone ? made : make_vertex(id);
  };
  const auto corner_id = [nv](int i, int j) {
    return GridTrimmer::kCornerBit | static_cast<std::uint32_t>(i * (nv + 1) + j);
  };
  const auto position = [&trimmer](std::uint32_t id) { return trimmer.position(id); };
  const double cell_area = 1.0 / (static_cast<double>(nu) * nv);
  const double degenerate_area2 = 1e-12 * cell_area;
  const double slack = 1e-9 / std::max(nu, nv);  // a piece's vertices may sit this far outside its cell

  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      switch (trimmer.kind(i, j)) {
        case CellKind::empty: break;
        case CellKind::full: {
          const std::uint32_t a = vertex(corner_id(i, j)), b = vertex(corner_id(i + 1, j));
          const std::uint32_t c = vertex(corner_id(i + 1, j + 1)), d = vertex(corner_id(i, j + 1));
          out.add_triangle(a, b, c);
          out.add_triangle(a, c, d);
          result.triangle_area += cell_area;
          break;
        }
        case CellKind::partial: {
          ++result.partial_cells;
          const double u0 = scratch.u_lines[i] - slack, u1 = scratch.u_lines[i + 1] + slack;
          const double v0 = scratch.v_lines[j] - slack, v1 = scratch.v_lines[j + 1] + slack;
          const auto in_cell = [&](const PolygonRing& ring) {
            return std::all_of(ring.begin(), ring.end(), [&](const PolygonVertex& p) {
              return p.uv.x >= u0 && p.uv.x <= u1 && p.uv.y >= v0 && p.uv.y <= v1;
            });
          };
          lap.to(Phase::trimmed_cells);
          const std::span<const TracedPiece> pieces = trimmer.trace(i, j);
          lap.to(Phase::trace);
          for (const TracedPiece& piece : pieces) {
            scratch.ring_triangles.clear();
            std::size_t ring_vertices = piece.outer.size();
            for (const PolygonRing& hole : piece.holes) ring_vertices += hole.size();
            // A large piece (a long trim polyline in one cell) gets the constrained triangulation; the planted bridge
            // defect belongs to ear clipping's hole joining, so a run that plants it keeps every piece there.
            const bool constrained = ring_vertices >= kConstrainedTriangulationMinVertices &&
                                     settings.planted_defect != PlantedDefect::bridge_to_first_copy &&
                                     triangulate_constrained(piece.outer, piece.holes, scratch.ring_triangles);
            if (constrained) {
              ++result.constrained_pieces;
            } else {
              scratch.ring = piece.outer;
              if (!piece.holes.empty()) {
                // Copied into rings that keep their capacity (assign() would free and reallocate them).
                if (scratch.holes.size() < piece.holes.size()) scratch.holes.resize(piece.holes.size());
                for (std::size_t h = 0; h < piece.holes.size(); ++h) scratch.holes[h] = piece.holes[h];
                join_holes(scratch.ring, std::span<PolygonRing>(scratch.holes.data(), piece.holes.size()),
                           settings.planted_defect == PlantedDefect::bridge_to_first_copy ? BridgeCopy::first_copy
                                                                                          : BridgeCopy::sector);
              }
              clip_ears(scratch.ring, scratch.ring_triangles, scratch.next, scratch.prev);
            }
            if (settings.planted_defect == PlantedDefect::drop_ear && scratch.ring_triangles.size() > 3) {
              scratch.ring_triangles.erase(scratch.ring_triangles.begin(), scratch.ring_triangles.begin() + 3);
            }
            lap.to(Phase::triangulate);
            const bool exact = scratch.tiling.check(piece.outer, piece.holes, scratch.ring_triangles, position,
                                                    degenerate_area2) == TilingVerdict::exact;
            const bool inside = in_cell(piece.outer) && std::all_of(piece.holes.begin(), piece.holes.end(), in_cell);
            if (!exact || !inside) ++result.tiling_violations;
            lap.to(Phase::audit);
            for (std::size_t t = 0; t < scratch.ring_triangles.size(); t += 3) {
              const std::uint32_t* tri = &scratch.ring_triangles[t];
              const double area2 = detail::cross2(position(tri[0]), position(tri[1]), position(tri[2]));
              if (area2 <= degenerate_area2) continue;  // degenerate: it only carried edges for the audit
              const std::uint32_t a = vertex(tri[0]), b = vertex(tri[1]), c = vertex(tri[2]);
              out.add_triangle(a, b, c);
              result.triangle_area += 0.5 * area2;
            }
          }
          break;
        }
      }
    }
  }
  lap.to(Phase::trimmed_cells);
  result.trace_failures = static_cast<std::uint32_t>(trimmer.inconsistencies());
  // Nudging trim points off grid lines (trim_region.hpp, step 1) moves each by at most 1e-6 of a cell, which
  // changes the enclosed area by at most perimeter · 1e-6 · cell size; anything beyond twice that is a defect.
  const double area_tolerance = 1e-12 + 2e-6 * perimeter / std::min(nu, nv);
  if (std::abs(result.triangle_area - result.trimmed_area) > area_tolerance) result.area_mismatches = 1;
  result.triangles = static_cast<std::uint32_t>(out.triangle_count());
  return result;
}

// Triangulates one surface by a plan made beforehand (plan_surface, possibly changed since, e.g. by a
// triangle budget: triangle_budget.hpp) into `out` (cleared first).
inline SurfaceResult tessellate_planned(const PreparedSurface& s, const SurfacePlan& plan,
                                        const TessellationSettings& settings, TessellationScratch& scratch,
                                        TriangleBuffers& out) {
  if (plan.culled != Culled::no) {
    out.clear();
    SurfaceResult culled;
    culled.culled = plan.culled;
    return culled;
  }
  if (s.trimmed()) return tessellate_trimmed(s, plan, settings, scratch, out);
  PhaseLap lap(scratch.profile);
  if (plan.single_precision) {
    tessellate_untrimmed_float(s.surface->patch, plan.steps, out, scratch.float_grid);
  } else {
    tessellate_untrimmed(s.surface->patch, plan.steps, out, scratch.grid_basis);
  }
  lap.to(Phase::untrimmed_grid);
  SurfaceResult r;
  r.steps = plan.steps;
  r.capped = plan.capped;
  r.triangles = static_cast<std::uint32_t>(out.triangle_count());
  return r;
}

// The whole per-frame step for one surface: cull, plan, triangulate into `out` (cleared first).
inline SurfaceResult tessellate_surface(const PreparedSurface& s, const Camera& camera, const Frustum& frustum,
                                        const TessellationSettings& settings, TessellationScratch& scratch,
                                        TriangleBuffers& out) {
  PhaseLap lap(scratch.profile);
  const SurfacePlan plan = plan_surface(s, camera, frustum, settings);
  lap.to(plan.culled == Culled::no ? Phase::plan : Phase::cull);
  return tessellate_planned(s, plan, settings, scratch, out);
}

}  // namespace frontsteal::tess
