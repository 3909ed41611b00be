// grid_audit.hpp — checks a uniform-grid tessellation of an untrimmed patch against the patch itself.
//
// Whatever produced the grid (the SIMD float row kernel, the double row evaluator, a GPU compute shader), its
// buffers are held against what the grid must be: (n_u+1)(n_v+1) vertices in row-major order along u, vertex
// (i, j) at S(i/n_u, j/n_v) evaluated exactly in double by bezier_patch.hpp's evaluate (the full tensor sum, not
// the collapsed rows that both fast paths use), its (u, v) the same, its normal the unit S_u × S_v, and the
// indices exactly grid_indices'. Positions may differ by the producer's stated error bound (float arithmetic);
// indices may not differ at all.
//
// Normals are compared only where they are well conditioned: where ‖S_u × S_v‖ ≥ 10⁻²·L² (L the diagonal of
// the control box), a float normal's direction error is below ~10⁻⁴ rad; nearer a collapsed edge (the teapot
// lid's pole) the float cross product is dominated by rounding and any direction is as good as another. Those
// vertices are counted, not compared.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/grid_tessellator.hpp"
#include "tessellate/step_sizes.hpp"

namespace frontsteal::tess {

struct GridAuditLimits {
  double position = 0;           // largest allowed distance from the exact point, object units
  double normal_radians = 1e-3;  // largest allowed angle to the exact normal, where it is well conditioned
  double uv = 1e-6;              // largest allowed error of a stored (u, v)
};

struct GridAudit {
  bool shape_ok = true;  // vertex, normal, uv and index counts as the grid needs
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  double max_position_error = 0;
  double max_normal_angle = 0;  // radians, over the well-conditioned vertices
  double max_uv_error = 0;
  std::size_t ill_conditioned_normals = 0;  // not compared (see above)
  std::size_t index_mismatches = 0;
  std::size_t failing_vertices = 0;  // beyond a limit in position, normal or (u, v)
  bool passed() const noexcept { return shape_ok && index_mismatches == 0 && failing_vertices == 0; }
};

inline GridAudit audit_grid(const BezierPatch& patch, StepSizes steps, const TriangleBuffers& grid,
                            const GridAuditLimits& limits) {
  GridAudit a;
  const int nu = steps.n_u, nv = steps.n_v;
  const std::size_t vertices = static_cast<std::size_t>(nu + 1) * static_cast<std::size_t>(nv + 1);
  const std::size_t indices = 6 * static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  a.vertices = grid.positions.size();
  a.triangles = grid.indices.size() / 3;
  if (grid.positions.size() != vertices || grid.normals.size() != vertices || grid.uvs.size() != vertices ||
      grid.indices.size() != indices) {
    a.shape_ok = false;
    return a;
  }
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (int i = 0; i <= patch.degree_u; ++i) {
    for (int j = 0; j <= patch.degree_v; ++j) {
      lo = glm::min(lo, patch.point(i, j));
      hi = glm::max(hi, patch.point(i, j));
    }
  }
  const double diagonal = glm::length(hi - lo);
  const double conditioned = 1e-2 * diagonal * diagonal;
  for (int i = 0; i <= nu; ++i) {
    for (int j = 0; j <= nv; ++j) {
      const double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
      const std::size_t k =
          static_cast<std::size_t>(i) * static_cast<std::size_t>(nv + 1) + static_cast<std::size_t>(j);
      const SurfacePoint exact = evaluate(patch, bernstein(patch.degree_u, u), bernstein(patch.degree_v, v));
      bool fails = false;
      const double position_error = glm::length(glm::dvec3(grid.positions[k]) - exact.position);
      a.max_position_error = std::max(a.max_position_error, position_error);
      fails |= !(position_error <= limits.position);  // NaN fails too
      const double uv_error =
          std::max(std::abs(static_cast<double>(grid.uvs[k].x) - u), std::abs(static_cast<double>(grid.uvs[k].y) - v));
      a.max_uv_error = std::max(a.max_uv_error, uv_error);
      fails |= !(uv_error <= limits.uv);
      if (glm::length(glm::cross(exact.du, exact.dv)) >= conditioned) {
        const glm::dvec3 n(grid.normals[k]);
        const double cosine = glm::dot(n, exact.normal) / std::max(glm::length(n), 1e-300);
        const double angle = std::acos(std::clamp(cosine, -1.0, 1.0));
        a.max_normal_angle = std::max(a.max_normal_angle, angle);
        fails |= !(angle <= limits.normal_radians);
      } else {
        ++a.ill_conditioned_normals;
      }
      a.failing_vertices += fails ? 1 : 0;
    }
  }
  std::vector<std::uint32_t> expected(indices);
  grid_indices(nu, nv, expected.data());
  for (std::size_t k = 0; k < indices; ++k) a.index_mismatches += expected[k] != grid.indices[k] ? 1 : 0;
  return a;
}

// The largest distance between the positions of two grids of the same shape (infinity when the shapes differ):
// how far two producers of the same grid disagree.
inline double max_position_difference(const TriangleBuffers& a, const TriangleBuffers& b) {
  if (a.positions.size() != b.positions.size()) return INFINITY;
  double worst = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) {
    const double d = glm::length(glm::dvec3(a.positions[k]) - glm::dvec3(b.positions[k]));
    worst = std::max(worst, std::isnan(d) ? INFINITY : d);
  }
  return worst;
}

}  // namespace frontsteal::tess
