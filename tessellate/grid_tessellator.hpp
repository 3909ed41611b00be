// grid_tessellator.hpp — an untrimmed patch as a uniform (n_u+1) × (n_v+1) grid of vertices, two triangles
// per cell split along the (i,j)–(i+1,j+1) diagonal. Rows are evaluated through RowCurve (below).
//
// Output goes into caller-owned buffers that keep their capacity across frames (clear() keeps it), so a
// steady-state frame allocates nothing. The basis in v is tabulated once per column and reused by every row.
// A pure function of (patch, steps): it can run on any worker, in any order, and twice without harm.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/grid_row_kernel.hpp"
#include "tessellate/step_sizes.hpp"

namespace frontsteal::tess {

struct TriangleBuffers {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;          // each vertex's (u, v): texture coordinates, and what tests check
  std::vector<std::uint32_t> indices;  // three per triangle

  void clear() noexcept {
    positions.clear();
    normals.clear();
    uvs.clear();
    indices.clear();
  }
  std::size_t triangle_count() const noexcept { return indices.size() / 3; }
  // One element at a time: vector::insert of an initializer list goes through a memcpy call per triangle.
  void add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    indices.push_back(a);
    indices.push_back(b);
    indices.push_back(c);
  }
  std::uint32_t add_vertex(const SurfacePoint& sp, double u, double v) {
    return add_vertex(glm::vec3(sp.position), glm::vec3(sp.normal), u, v);
  }
  std::uint32_t add_vertex(const glm::vec3& position, const glm::vec3& normal, double u, double v) {
    positions.push_back(position);
    normals.push_back(normal);
    uvs.emplace_back(static_cast<float>(u), static_cast<float>(v));
    return static_cast<std::uint32_t>(positions.size() - 1);
  }
};

// One row of the grid at fixed u: the patch collapsed to a curve in v (homogeneous control values R_j and
// their u-derivatives D_j), so each vertex costs 3(n+1) multiply-adds instead of 3(m+1)(n+1).
//
// Entries past degree_v are left unwritten (collapse() writes 0..degree_v, at() reads no further): zero-filling
// the 2×26 dvec4 of the degree-25 bound would cost more than collapsing a bicubic row.
struct RowCurve {
  std::array<glm::dvec4, kMaxDegree + 1> value, du;

  void collapse(const BezierPatch& p, const BernsteinTable& bu) noexcept {
    for (int j = 0; j <= p.degree_v; ++j) {
      glm::dvec4 r(0.0), d(0.0);
      for (int i = 0; i <= p.degree_u; ++i) {
        const glm::dvec4& h = p.homogeneous(i, j);
        r += bu.value[i] * h;
        d += bu.derivative[i] * h;
      }
      value[j] = r;
      du[j] = d;
    }
  }
  SurfacePoint at(int degree_v, const BernsteinTable& bv) const noexcept {
    glm::dvec4 s(0.0), su(0.0), sv(0.0);
    for (int j = 0; j <= degree_v; ++j) {
      s += bv.value[j] * value[j];
      su += bv.value[j] * du[j];
      sv += bv.derivative[j] * value[j];
    }
    SurfacePoint out;
    const double inv_w = 1.0 / s.w;
    out.position = glm::dvec3(s) * inv_w;
    out.du = (glm::dvec3(su) - out.position * su.w) * inv_w;  // quotient rule
    out.dv = (glm::dvec3(sv) - out.position * sv.w) * inv_w;
    const glm::dvec3 n = glm::cross(out.du, out.dv);
    const double len2 = glm::dot(n, n);
    out.normal = len2 > 0.0 ? n / std::sqrt(len2) : glm::dvec3(0.0);
    return out;
  }
};

// Two triangles per cell, counter-clockwise seen from the side the normal S_u × S_v points to.
inline void grid_indices(int nu, int nv, std::uint32_t* index) noexcept {
  for (int i = 0; i < nu; ++i) {
    const std::uint32_t row0 = static_cast<std::uint32_t>(i * (nv + 1));
    const std::uint32_t row1 = row0 + static_cast<std::uint32_t>(nv + 1);
    for (int j = 0; j < nv; ++j) {
      const std::uint32_t a = row0 + j, b = row1 + j;
      index[0] = a, index[1] = b, index[2] = b + 1;
      index[3] = a, index[4] = b + 1, index[5] = a + 1;
      index += 6;
    }
  }
}

// Scratch of the single-precision path; keeps its capacity across surfaces and frames.
struct FloatGridScratch {
  std::vector<float> basis, derivative, rows;
  std::vector<std::uint8_t> degenerate;
  // The v-basis tables above were made for this degree and n_v: consecutive surfaces of one scene mostly share
  // both, and then the tables are reused as they are.
  int basis_degree = -1, basis_steps = -1;
};

// Makes the scratch's v-basis tables for (degree_v, n_v) unless it holds them already, and sizes its row
// scratch: what float_grid_row (below) needs before the rows of one grid.
inline void prepare_float_grid(int degree_v, int nv, FloatGridScratch& scratch) {
  const int n = nv + 1, padded = padded_row(n);
  scratch.rows.resize(static_cast<std::size_t>(6 * padded));
  scratch.degenerate.resize(static_cast<std::size_t>(n));
  if (scratch.basis_degree == degree_v && scratch.basis_steps == nv) return;
  scratch.basis.assign(static_cast<std::size_t>((degree_v + 1) * padded), 0.0f);
  scratch.derivative.assign(scratch.basis.size(), 0.0f);
  for (int j = 0; j <= nv; ++j) {
    const BernsteinTable b = bernstein(degree_v, static_cast<double>(j) / nv);
    for (int k = 0; k <= degree_v; ++k) {
      scratch.basis[static_cast<std::size_t>(k * padded + j)] = static_cast<float>(b.value[k]);
      scratch.derivative[static_cast<std::size_t>(k * padded + j)] = static_cast<float>(b.derivative[k]);
    }
  }
  scratch.basis_degree = degree_v;
  scratch.basis_steps = nv;
}

// The grid row at parameter u (vertices v = j / n_v, j = 0..n_v) by the SIMD float kernel: positions and unit
// normals into `position` / `normal` (x, y, z per vertex); scratch.degenerate[j] = 1 where the normal vanished
// (a collapsed edge: the caller takes that normal from the double evaluator). prepare_float_grid first.
inline void float_grid_row(const BezierPatch& patch, const BernsteinTable& u_basis, int nv, FloatGridScratch& scratch,
                           glm::vec3* position, glm::vec3* normal) {
  RowCurve row;
  row.collapse(patch, u_basis);  // in double: (m+1)(n+1) terms per row, not per vertex
  RowKernelArgs args;
  args.degree_v = patch.degree_v;
  args.count = nv + 1;
  args.basis = scratch.basis.data();
  args.derivative = scratch.derivative.data();
  args.degenerate = scratch.degenerate.data();
  args.scratch = scratch.rows.data();
  for (int k = 0; k <= patch.degree_v; ++k) {
    for (int c = 0; c < 4; ++c) {
      args.value[k][c] = static_cast<float>(row.value[k][c]);
      args.du[k][c] = static_cast<float>(row.du[k][c]);
    }
  }
  args.position = &position->x;
  args.normal = &normal->x;
  evaluate_row_float(args);
}

// The same grid as tessellate_untrimmed (below), each row by the SIMD float kernel (grid_row_kernel.hpp).
// Use only where float_row_error_bound(patch) is well inside the tolerance (plan_surface decides).
inline void tessellate_untrimmed_float(const BezierPatch& patch, StepSizes steps, TriangleBuffers& out,
                                       FloatGridScratch& scratch) {
  // No clear(): every element is overwritten below, and resizing a buffer that already holds this surface's
  // last grid (the steady state) writes nothing, where clear() + resize() zero-filled it all first.
  const int nu = steps.n_u, nv = steps.n_v, n = nv + 1;
  prepare_float_grid(patch.degree_v, nv, scratch);
  const std::size_t vertices = static_cast<std::size_t>((nu + 1) * n);
  out.positions.resize(vertices);
  out.normals.resize(vertices);
  out.uvs.resize(vertices);
  out.indices.resize(static_cast<std::size_t>(6 * nu * nv));
  for (int i = 0; i <= nu; ++i) {
    const double u = static_cast<double>(i) / nu;
    const std::size_t first = static_cast<std::size_t>(i * n);
    float_grid_row(patch, bernstein(patch.degree_u, u), nv, scratch, &out.positions[first], &out.normals[first]);
    for (int j = 0; j <= nv; ++j) {
      out.uvs[first + static_cast<std::size_t>(j)] =
          glm::vec2(static_cast<float>(u), static_cast<float>(j) / static_cast<float>(nv));
      if (scratch.degenerate[static_cast<std::size_t>(j)]) [[unlikely]] {  // collapsed edge
        out.normals[first + static_cast<std::size_t>(j)] =
            glm::vec3(evaluate(patch, u, static_cast<double>(j) / nv).normal);
      }
    }
  }
  grid_indices(nu, nv, out.indices.data());
}

inline void tessellate_untrimmed(const BezierPatch& patch, StepSizes steps, TriangleBuffers& out,
                                 std::vector<BernsteinTable>& v_basis_scratch) {
  // No clear(), as in tessellate_untrimmed_float: every element is overwritten.
  const int nu = steps.n_u;
  const int nv = steps.n_v;
  v_basis_scratch.resize(static_cast<std::size_t>(nv + 1));
  for (int j = 0; j <= nv; ++j) v_basis_scratch[j] = bernstein(patch.degree_v, static_cast<double>(j) / nv);
  RowCurve row;
  // Sized once (capacity kept across frames), then written in place: no per-element growth checks.
  const std::size_t vertices = static_cast<std::size_t>((nu + 1) * (nv + 1));
  out.positions.resize(vertices);
  out.normals.resize(vertices);
  out.uvs.resize(vertices);
  out.indices.resize(static_cast<std::size_t>(6 * nu * nv));
  glm::vec3* position = out.positions.data();
  glm::vec3* normal = out.normals.data();
  glm::vec2* uv = out.uvs.data();
  // Vertices, row by row along u.
  for (int i = 0; i <= nu; ++i) {
    const double u = static_cast<double>(i) / nu;
    row.collapse(patch, bernstein(patch.degree_u, u));
    for (int j = 0; j <= nv; ++j) {
      const double v = static_cast<double>(j) / nv;
      SurfacePoint sp = row.at(patch.degree_v, v_basis_scratch[j]);
      if (sp.normal == glm::dvec3(0.0)) [[unlikely]]
        sp.normal = evaluate(patch, u, v).normal;  // collapsed edge
      *position++ = glm::vec3(sp.position);
      *normal++ = glm::vec3(sp.normal);
      *uv++ = glm::vec2(static_cast<float>(u), static_cast<float>(v));
    }
  }
  grid_indices(nu, nv, out.indices.data());
}

}  // namespace frontsteal::tess
