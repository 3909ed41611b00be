// grid_tessellator.hpp — an untrimmed patch as a uniform (n_u+1) × (n_v+1) grid of vertices, two triangles
// per cell split along the (i,j)–(i+1,j+1) diagonal.
//
// Output goes into caller-owned buffers that keep their capacity across frames (clear() keeps it), so a
// steady-state frame allocates nothing. The basis in v is tabulated once per column and reused by every row.
// A pure function of (patch, steps): it can run on any worker, in any order, and twice without harm.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/step_sizes.hpp"

namespace frontsteal::tess {

struct TriangleBuffers {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<std::uint32_t> indices;  // three per triangle

  void clear() noexcept {
    positions.clear();
    normals.clear();
    indices.clear();
  }
  std::size_t triangle_count() const noexcept { return indices.size() / 3; }
};

inline void tessellate_untrimmed(const BezierPatch& patch, StepSizes steps, TriangleBuffers& out,
                                 std::vector<BernsteinTable>& v_basis_scratch) {
  out.clear();
  const int nu = steps.n_u;
  const int nv = steps.n_v;
  v_basis_scratch.resize(static_cast<std::size_t>(nv + 1));
  for (int j = 0; j <= nv; ++j) v_basis_scratch[j] = bernstein(patch.degree_v, static_cast<double>(j) / nv);
  // Vertices, row by row along u.
  for (int i = 0; i <= nu; ++i) {
    const double u = static_cast<double>(i) / nu;
    const BernsteinTable bu = bernstein(patch.degree_u, u);
    for (int j = 0; j <= nv; ++j) {
      SurfacePoint sp = evaluate(patch, bu, v_basis_scratch[j]);
      if (sp.normal == glm::dvec3(0.0)) sp.normal = evaluate(patch, u, static_cast<double>(j) / nv).normal;
      out.positions.emplace_back(sp.position);
      out.normals.emplace_back(sp.normal);
    }
  }
  // Two triangles per cell, counter-clockwise seen from the side the normal S_u × S_v points to.
  const auto at = [nv](int i, int j) { return static_cast<std::uint32_t>(i * (nv + 1) + j); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      out.indices.insert(out.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      out.indices.insert(out.indices.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
}

}  // namespace frontsteal::tess
