// culling.hpp — view-independent bounds of a patch, and the per-frame tests that discard invisible patches.
//
// Both tests are conservative: they may keep an invisible patch, never drop a visible one.
//   Frustum: a rational Bézier patch with positive weights lies in the convex hull of its control points, so
//   in their bounding box; a box whose 8 corners are all outside one frustum plane is invisible.
//   Back faces (Shirman & Abi-Ezzi, "The cone of normals technique for fast processing of curved patches",
//   Eurographics 1993): the normal N = S_u × S_v is itself a Bézier patch whose control vectors do not depend
//   on the view; a cone (axis a, half-angle α < 90°) containing them contains every normal. With the patch in
//   a sphere (c, r), eye e, D = |c − e| > r, β = ∠(a, c − e), γ = asin(r / D): the patch faces away from the
//   eye everywhere when every normal n and every view direction p − e make an angle below 90°, which holds
//   when β + α + γ < 90°. Only surfaces of closed solids
//   (Surface::solid) may be culled this way: an open sheet's back is visible.
//   Rational patches: S = X / W gives S_u × S_v = [W (X_u × X_v) + W_v (X × X_u) + W_u (X_v × X)] / W³, and
//   W > 0, so the bracket — a polynomial patch of degree (3m−1, 3n−1) — has the normal's direction. Its control
//   vectors come from products of Bézier patches in Bernstein form:
//     (A·B)_{kl} = Σ C(a₁,i)C(b₁,k−i)/C(a₁+b₁,k) · C(a₂,j)C(b₂,l−j)/C(a₂+b₂,l) · A_ij B_{k−i,l−j}.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/camera.hpp"

namespace frontsteal::tess {

struct Box {
  glm::dvec3 lo{0.0}, hi{0.0};
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
  glm::dvec3 corner(int k) const { return {(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z}; }
};

struct NormalCone {
  glm::dvec3 axis{0.0};
  double half_angle = std::numbers::pi;  // ≥ 90°: no cone (back-face culling impossible)
  bool usable() const noexcept { return half_angle < 0.5 * std::numbers::pi; }
};

// Control values of a tensor-product Bézier function of degrees (du, dv), row-major i along u.
template <class T>
struct BernsteinGrid {
  int du = 0, dv = 0;
  std::vector<T> c;
  const T& at(int i, int j) const { return c[static_cast<std::size_t>(i * (dv + 1) + j)]; }
  T& at(int i, int j) { return c[static_cast<std::size_t>(i * (dv + 1) + j)]; }
};

namespace detail {

inline double binomial(int n, int k) {
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

template <class A, class B, class Op>
auto bernstein_product(const BernsteinGrid<A>& a, const BernsteinGrid<B>& b, Op op) {
  using T = decltype(op(a.c[0], b.c[0]));
  BernsteinGrid<T> out{a.du + b.du, a.dv + b.dv, {}};
  out.c.assign(static_cast<std::size_t>((out.du + 1) * (out.dv + 1)), T{});
  for (int i = 0; i <= a.du; ++i) {
    for (int j = 0; j <= a.dv; ++j) {
      for (int k = 0; k <= b.du; ++k) {
        for (int l = 0; l <= b.dv; ++l) {
          const double f = binomial(a.du, i) * binomial(b.du, k) / binomial(out.du, i + k) * binomial(a.dv, j) *
                           binomial(b.dv, l) / binomial(out.dv, j + l);
          out.at(i + k, j + l) += f * op(a.at(i, j), b.at(k, l));
        }
      }
    }
  }
  return out;
}

template <class T>
BernsteinGrid<T> derivative_u(const BernsteinGrid<T>& g) {
  BernsteinGrid<T> d{g.du - 1, g.dv, std::vector<T>(static_cast<std::size_t>(g.du * (g.dv + 1)))};
  for (int i = 0; i < g.du; ++i) {
    for (int j = 0; j <= g.dv; ++j) d.at(i, j) = static_cast<double>(g.du) * (g.at(i + 1, j) - g.at(i, j));
  }
  return d;
}

template <class T>
BernsteinGrid<T> derivative_v(const BernsteinGrid<T>& g) {
  BernsteinGrid<T> d{g.du, g.dv - 1, std::vector<T>(static_cast<std::size_t>((g.du + 1) * g.dv))};
  for (int i = 0; i <= g.du; ++i) {
    for (int j = 0; j < g.dv; ++j) d.at(i, j) = static_cast<double>(g.dv) * (g.at(i, j + 1) - g.at(i, j));
  }
  return d;
}

}  // namespace detail

inline Box control_box(const BezierPatch& p) {
  Box b{p.point(0, 0), p.point(0, 0)};
  for (int i = 0; i <= p.degree_u; ++i) {
    for (int j = 0; j <= p.degree_v; ++j) {
      b.lo = glm::min(b.lo, p.point(i, j));
      b.hi = glm::max(b.hi, p.point(i, j));
    }
  }
  return b;
}

// Control vectors of the (unnormalized) normal direction: W (X_u × X_v) + W_v (X × X_u) + W_u (X_v × X).
inline BernsteinGrid<glm::dvec3> normal_control_vectors(const BezierPatch& p) {
  BernsteinGrid<glm::dvec3> x{p.degree_u, p.degree_v, {}};
  BernsteinGrid<double> w{p.degree_u, p.degree_v, {}};
  for (const glm::dvec4& h : p.control) {
    x.c.push_back(glm::dvec3(h));
    w.c.push_back(h.w);
  }
  const auto xu = detail::derivative_u(x), xv = detail::derivative_v(x);
  const auto wu = detail::derivative_u(w), wv = detail::derivative_v(w);
  const auto cross = [](const glm::dvec3& a, const glm::dvec3& b) { return glm::cross(a, b); };
  const auto scale = [](double s, const glm::dvec3& v) { return s * v; };
  auto n = detail::bernstein_product(w, detail::bernstein_product(xu, xv, cross), scale);
  const auto b = detail::bernstein_product(wv, detail::bernstein_product(x, xu, cross), scale);
  const auto c = detail::bernstein_product(wu, detail::bernstein_product(xv, x, cross), scale);
  for (std::size_t k = 0; k < n.c.size(); ++k) n.c[k] += b.c[k] + c.c[k];
  return n;
}

inline NormalCone normal_cone(const BezierPatch& p) {
  const BernsteinGrid<glm::dvec3> n = normal_control_vectors(p);
  double scale = 0;
  for (const glm::dvec3& v : n.c) scale = std::max(scale, glm::length(v));
  NormalCone cone;
  if (!(scale > 0)) return cone;
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& v : n.c) {
    const double len = glm::length(v);
    if (len > 1e-12 * scale) sum += v / len;
  }
  if (glm::length(sum) == 0) return cone;
  cone.axis = glm::normalize(sum);
  double widest = 0;
  for (const glm::dvec3& v : n.c) {
    const double len = glm::length(v);
    if (len <= 1e-12 * scale) continue;  // a zero control vector adds nothing to N's direction
    widest = std::max(widest, std::acos(std::clamp(glm::dot(cone.axis, v / len), -1.0, 1.0)));
  }
  cone.half_angle = widest + 1e-9;
  return cone;
}

// Frustum test on the control box.
inline bool outside_frustum(const Box& box, const Frustum& frustum) {
  for (const glm::dvec4& plane : frustum.planes) {
    bool all_out = true;
    for (int k = 0; k < 8 && all_out; ++k) all_out = glm::dot(plane, glm::dvec4(box.corner(k), 1.0)) < 0;
    if (all_out) return true;
  }
  return false;
}

// Cone-of-normals test: true when every point of the patch faces away from `eye`.
inline bool faces_away(const NormalCone& cone, const glm::dvec3& centre, double radius, const glm::dvec3& eye) {
  if (!cone.usable()) return false;
  const glm::dvec3 to_patch = centre - eye;
  const double distance = glm::length(to_patch);
  if (distance <= radius) return false;
  const double beta = std::acos(std::clamp(glm::dot(cone.axis, to_patch / distance), -1.0, 1.0));
  const double gamma = std::asin(radius / distance);
  return beta + cone.half_angle + gamma < 0.5 * std::numbers::pi;
}

}  // namespace frontsteal::tess
