// bezier_patch.hpp — rational tensor-product Bézier patches and their evaluation.
//
// S(u, v) = Σ_i Σ_j B_i^m(u) B_j^n(v) w_ij P_ij / Σ_i Σ_j B_i^m(u) B_j^n(v) w_ij,   (u, v) ∈ [0,1]²
// with B_i^m the Bernstein polynomials of degree m. Control points are stored homogeneous, H_ij =
// (w P, w), row-major with i along u. Degrees 1..kMaxDegree in each direction; weights must be > 0 (the
// convex-hull property culling relies on).
//
// Evaluation tabulates B and B' in u and in v, sums the homogeneous point and its two partial derivatives,
// and divides out (quotient rule): P = S/w, P_u = (S_u − P w_u)/w, likewise P_v. The normal is P_u × P_v,
// normalized; where that vanishes (a collapsed edge, e.g. the teapot lid's pole) it is taken a hair inside
// the patch instead.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace frontsteal::tess {

// Open CASCADE's own limit for B-spline degrees (BSplCLib::MaxDegree()), so that any face a CAD file can hold
// is evaluated at its own degree rather than approximated or skipped.
inline constexpr int kMaxDegree = 25;

struct BezierPatch {
  int degree_u = 3;
  int degree_v = 3;
  std::vector<glm::dvec4> control;  // homogeneous (w·x, w·y, w·z, w), index i·(degree_v+1) + j

  BezierPatch() = default;
  BezierPatch(int du, int dv) : degree_u(du), degree_v(dv), control(static_cast<std::size_t>((du + 1) * (dv + 1))) {
    if (du < 1 || du > kMaxDegree || dv < 1 || dv > kMaxDegree) {
      throw std::invalid_argument("Bézier patch degree must be 1.." + std::to_string(kMaxDegree) + ", got " +
                                  std::to_string(du) + "x" + std::to_string(dv));
    }
  }

  std::size_t index(int i, int j) const noexcept { return static_cast<std::size_t>(i * (degree_v + 1) + j); }
  const glm::dvec4& homogeneous(int i, int j) const noexcept { return control[index(i, j)]; }
  double weight(int i, int j) const noexcept { return control[index(i, j)].w; }
  glm::dvec3 point(int i, int j) const noexcept {
    const glm::dvec4& h = control[index(i, j)];
    return glm::dvec3(h) / h.w;
  }
  void set(int i, int j, const glm::dvec3& p, double w = 1.0) noexcept { control[index(i, j)] = glm::dvec4(p * w, w); }
};

struct SurfacePoint {
  glm::dvec3 position;
  glm::dvec3 du;  // ∂S/∂u
  glm::dvec3 dv;  // ∂S/∂v
  glm::dvec3 normal;
};

// Bernstein basis B_i^d(t), i = 0..d, and its derivative, by the triangle recurrence (stable on [0,1]).
// Entries past the degree are not written by bernstein() and never read: the tables are sized for degree 25,
// and zero-filling 2×26 doubles per call cost more than the recurrence at the usual degrees.
struct BernsteinTable {
  std::array<double, kMaxDegree + 1> value;
  std::array<double, kMaxDegree + 1> derivative;
};

namespace detail {

// bernstein() and evaluate() below with the degrees known at compile time where D, M, N > 0 (0: read at run
// time), so that the common degrees unroll; always inlined, so that evaluate()'s AVX2 build (bezier_patch.cpp)
// compiles them for AVX2. The operations and their order are the same either way, so the results are the same bits.
template <int D>
[[gnu::always_inline]] inline BernsteinTable bernstein_of(int run_time_degree, double t) noexcept {
  const int degree = D > 0 ? D : run_time_degree;
  // Degree d-1 values first: B'_i^d = d (B_{i-1}^{d-1} − B_i^{d-1}).
  std::array<double, kMaxDegree + 1> b;  // b[0..d] written before they are read, d = 0..degree-1
  b[0] = 1.0;
  const double s = 1.0 - t;
  for (int d = 1; d < degree; ++d) {
    double carry = 0.0;
    for (int i = 0; i < d; ++i) {
      const double keep = b[i];
      b[i] = carry + s * keep;
      carry = t * keep;
    }
    b[d] = carry;
  }
  BernsteinTable out;
  for (int i = 0; i <= degree; ++i) {
    const double lower = i > 0 ? b[i - 1] : 0.0;
    const double same = i < degree ? b[i] : 0.0;
    out.derivative[i] = degree * (lower - same);
  }
  // Raise the degree-(d-1) values to degree d for the values themselves.
  double carry = 0.0;
  for (int i = 0; i < degree; ++i) {
    out.value[i] = carry + s * b[i];
    carry = t * b[i];
  }
  out.value[degree] = carry;
  return out;
}

// The sums of evaluate_of in glm::dvec4 (the default), or in a type of four lanes with the same lane-wise + and
// scalar × (bezier_patch.cpp's GCC vector); lane-wise, either way, so the same bits.
template <class Lanes4>
struct HomogeneousSum {
  [[gnu::always_inline]] static Lanes4 of(const glm::dvec4& h) noexcept {
    Lanes4 v;
    __builtin_memcpy(&v, &h, sizeof v);
    return v;
  }
  [[gnu::always_inline]] static glm::dvec4 to_glm(const Lanes4& v) noexcept {
    glm::dvec4 h;
    __builtin_memcpy(&h, &v, sizeof h);
    return h;
  }
};
template <>
struct HomogeneousSum<glm::dvec4> {
  static const glm::dvec4& of(const glm::dvec4& h) noexcept { return h; }
  static const glm::dvec4& to_glm(const glm::dvec4& h) noexcept { return h; }
};

template <int M, int N, class Lanes4 = glm::dvec4>
[[gnu::always_inline]] inline SurfacePoint evaluate_of(const BezierPatch& p, const BernsteinTable& bu,
                                                       const BernsteinTable& bv) noexcept {
  using Sum = HomogeneousSum<Lanes4>;
  const int degree_u = M > 0 ? M : p.degree_u, degree_v = N > 0 ? N : p.degree_v;
  Lanes4 s_sum = Sum::of(glm::dvec4(0.0)), su_sum = s_sum, sv_sum = s_sum;
  for (int i = 0; i <= degree_u; ++i) {
    Lanes4 row = Sum::of(glm::dvec4(0.0)), row_dv = row;
    for (int j = 0; j <= degree_v; ++j) {
      const Lanes4 h = Sum::of(p.control[static_cast<std::size_t>(i * (degree_v + 1) + j)]);
      row += bv.value[j] * h;
      row_dv += bv.derivative[j] * h;
    }
    s_sum += bu.value[i] * row;
    su_sum += bu.derivative[i] * row;
    sv_sum += bu.value[i] * row_dv;
  }
  const glm::dvec4 s = Sum::to_glm(s_sum), su = Sum::to_glm(su_sum), sv = Sum::to_glm(sv_sum);
  SurfacePoint out;
  out.position = glm::dvec3(s) / s.w;
  out.du = (glm::dvec3(su) - out.position * su.w) / s.w;  // quotient rule
  out.dv = (glm::dvec3(sv) - out.position * sv.w) / s.w;
  const glm::dvec3 n = glm::cross(out.du, out.dv);
  const double len = glm::length(n);
  out.normal = len > 0.0 ? n / len : glm::dvec3(0.0);
  return out;
}

template <int M, int N, class Lanes4 = glm::dvec4>
[[gnu::always_inline]] inline SurfacePoint evaluate_at(const BezierPatch& p, double u, double v) noexcept {
  return evaluate_of<M, N, Lanes4>(p, bernstein_of<M>(p.degree_u, u), bernstein_of<N>(p.degree_v, v));
}

}  // namespace detail

inline BernsteinTable bernstein(int degree, double t) noexcept { return detail::bernstein_of<0>(degree, t); }

// Position, partial derivatives and unit normal at (u, v), from precomputed basis tables.
inline SurfacePoint evaluate(const BezierPatch& p, const BernsteinTable& bu, const BernsteinTable& bv) noexcept {
  return detail::evaluate_of<0, 0>(p, bu, bv);
}

// Position, partial derivatives and unit normal at (u, v) (bezier_patch.cpp). A collapsed edge's vanished
// normal is taken a hair towards the patch centre, where the surface is regular.
SurfacePoint evaluate(const BezierPatch& p, double u, double v) noexcept;

}  // namespace frontsteal::tess
