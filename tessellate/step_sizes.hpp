// step_sizes.hpp — how finely to sample a patch: uniform step counts n_u, n_v from a tolerance.
//
// Deviation bound (Filip, Magedson & Markot, "Surface algorithms using bounds on derivatives", CAGD 3, 1986):
// on a grid of steps δu = 1/n_u, δv = 1/n_v, the distance between the surface and its piecewise-linear
// interpolant is at most
//     (1/8) (δu² M_uu + 2 δu δv M_uv + δv² M_vv),
// with M_uu ≤ m(m−1) max‖Δ_uu P‖, M_uv ≤ m n max‖Δ_uv P‖, M_vv ≤ n(n−1) max‖Δ_vv P‖ (second differences of
// the control net; m, n the degrees). The steps with the fewest cells n_u·n_v that meet (1/8)(…) ≤ ε: with
// s = √(M_uu / M_vv), δu/δv = 1/s balances the two squares (A a² + C b² ≥ 2√(AC) ab, equality at A a² = C b²) and
//     n_u = ⌈ sqrt((M_uu + M_uv·s) / (4ε)) ⌉,   n_v = ⌈ sqrt((M_vv + M_uv/s) / (4ε)) ⌉,
// which meet the bound exactly before rounding up (substitute: each square gives 4ε·M/(M + M_uv·…) and the
// mixed term the rest). Where M_uu or M_vv is 0 (a straight direction) the even split is kept:
//     n_u = ⌈ sqrt((M_uu + M_uv) / (4ε)) ⌉,   n_v = ⌈ sqrt((M_vv + M_uv) / (4ε)) ⌉
// (2ab ≤ a² + b²: each direction gets half the tolerance).
// The M's must bound the second derivatives of the *surface*. For a rational patch S = X / W (X the weighted
// points, W the weight, both polynomial) they follow from the quotient rule, with the origin moved to the
// centre c of the control net's bounding box so that ‖S‖ ≤ R = max‖P_ij − c‖ (convex hull, weights > 0):
//     ‖S_u‖  ≤ (‖X_u‖ + R |W_u|) / w_min
//     ‖S_uu‖ ≤ (‖X_uu‖ + 2 ‖S_u‖ |W_u| + R |W_uu|) / w_min
//     ‖S_uv‖ ≤ (‖X_uv‖ + ‖S_u‖ |W_v| + ‖S_v‖ |W_u| + R |W_uv|) / w_min
// and the polynomial derivatives are bounded by differences of the control values: ‖X_u‖ ≤ m max‖ΔX‖,
// ‖X_uu‖ ≤ m(m−1) max‖Δ²X‖, ‖X_uv‖ ≤ m n max‖Δ_uv X‖ (same for W). For w ≡ 1 this is exactly the
// polynomial bound above. (A first version scaled the Cartesian differences by (w_max/w_min)²; the fixed-seed
// property test found a rational bilinear patch it under-sampled, since a bilinear net has no second
// differences while the rational surface still curves.)
//
// Size bound: grid edges along u and v no longer than a length ℓ: n_u = ⌈ max‖S_u‖ / ℓ ⌉ (for a polynomial
// patch max‖S_u‖ ≤ m · max‖P_{i+1,j} − P_ij‖), likewise n_v. Diagonals are then at most 2ℓ.
//
// Screen space: a pixel tolerance becomes an object-space one per patch and frame as
//     ε_obj = ε_px · d_min / f_px,   f_px = (H/2) / tan(fovy/2),
// with d_min the nearest distance of the patch's bounding box along the view axis (at least the near plane).
#pragma once

#include <algorithm>
#include <cmath>

#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess {

struct StepSizes {
  int n_u = 1;
  int n_v = 1;
  friend bool operator==(const StepSizes&, const StepSizes&) = default;
};

struct NetBounds {
  double m_uu = 0, m_uv = 0, m_vv = 0;  // bounds on ‖S_uu‖, ‖S_uv‖, ‖S_vv‖
  double len_u = 0, len_v = 0;          // bounds on ‖S_u‖, ‖S_v‖
};

inline NetBounds net_bounds(const BezierPatch& p) {
  const int m = p.degree_u;
  const int n = p.degree_v;
  // Centre of the control net's bounding box, radius around it, smallest weight.
  glm::dvec3 lo = p.point(0, 0), hi = lo;
  double w_min = p.weight(0, 0);
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= n; ++j) {
      lo = glm::min(lo, p.point(i, j));
      hi = glm::max(hi, p.point(i, j));
      w_min = std::min(w_min, p.weight(i, j));
    }
  }
  const glm::dvec3 c = 0.5 * (lo + hi);
  double radius = 0;
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= n; ++j) radius = std::max(radius, glm::length(p.point(i, j) - c));
  }
  // Homogeneous control values about c: X_ij = w_ij (P_ij − c), W_ij = w_ij.
  const auto x = [&](int i, int j) { return p.weight(i, j) * (p.point(i, j) - c); };
  const auto w = [&](int i, int j) { return p.weight(i, j); };
  double xu = 0, wu = 0, xv = 0, wv = 0, xuu = 0, wuu = 0, xvv = 0, wvv = 0, xuv = 0, wuv = 0;
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j <= n; ++j) {
      if (i + 1 <= m) {
        xu = std::max(xu, glm::length(x(i + 1, j) - x(i, j)));
        wu = std::max(wu, std::abs(w(i + 1, j) - w(i, j)));
      }
      if (j + 1 <= n) {
        xv = std::max(xv, glm::length(x(i, j + 1) - x(i, j)));
        wv = std::max(wv, std::abs(w(i, j + 1) - w(i, j)));
      }
      if (i + 2 <= m) {
        xuu = std::max(xuu, glm::length(x(i + 2, j) - 2.0 * x(i + 1, j) + x(i, j)));
        wuu = std::max(wuu, std::abs(w(i + 2, j) - 2.0 * w(i + 1, j) + w(i, j)));
      }
      if (j + 2 <= n) {
        xvv = std::max(xvv, glm::length(x(i, j + 2) - 2.0 * x(i, j + 1) + x(i, j)));
        wvv = std::max(wvv, std::abs(w(i, j + 2) - 2.0 * w(i, j + 1) + w(i, j)));
      }
      if (i + 1 <= m && j + 1 <= n) {
        xuv = std::max(xuv, glm::length(x(i + 1, j + 1) - x(i + 1, j) - x(i, j + 1) + x(i, j)));
        wuv = std::max(wuv, std::abs(w(i + 1, j + 1) - w(i + 1, j) - w(i, j + 1) + w(i, j)));
      }
    }
  }
  // Degree factors turn differences into derivative bounds.
  xu *= m, wu *= m, xv *= n, wv *= n;
  xuu *= m * (m - 1), wuu *= m * (m - 1), xvv *= n * (n - 1), wvv *= n * (n - 1), xuv *= m * n, wuv *= m * n;
  NetBounds b;
  b.len_u = (xu + radius * wu) / w_min;
  b.len_v = (xv + radius * wv) / w_min;
  b.m_uu = (xuu + 2 * b.len_u * wu + radius * wuu) / w_min;
  b.m_vv = (xvv + 2 * b.len_v * wv + radius * wvv) / w_min;
  b.m_uv = (xuv + b.len_u * wv + b.len_v * wu + radius * wuv) / w_min;
  return b;
}

// Steps for a deviation of at most `epsilon` (object space), clamped to [1, max_steps].
inline StepSizes deviation_steps(const NetBounds& b, double epsilon, int max_steps = 1024) {
  auto steps = [&](double m) {
    const double n = std::ceil(std::sqrt(m / (4.0 * epsilon)));
    return static_cast<int>(std::clamp(n, 1.0, static_cast<double>(max_steps)));
  };
  if (b.m_uu > 0 && b.m_vv > 0) {
    const double s = std::sqrt(b.m_uu / b.m_vv);
    return {steps(b.m_uu + b.m_uv * s), steps(b.m_vv + b.m_uv / s)};
  }
  return {steps(b.m_uu + b.m_uv), steps(b.m_vv + b.m_uv)};
}

// Steps for triangle edges of at most `edge_length`, clamped to [1, max_steps].
inline StepSizes size_steps(const NetBounds& b, double edge_length, int max_steps = 1024) {
  auto steps = [&](double len) {
    return static_cast<int>(std::clamp(std::ceil(len / edge_length), 1.0, static_cast<double>(max_steps)));
  };
  return {steps(b.len_u), steps(b.len_v)};
}

// Both bounds: deviation ≤ epsilon and edges ≤ edge_length.
inline StepSizes step_sizes(const BezierPatch& p, double epsilon, double edge_length, int max_steps = 1024) {
  const NetBounds b = net_bounds(p);
  const StepSizes d = deviation_steps(b, epsilon, max_steps);
  const StepSizes s = size_steps(b, edge_length, max_steps);
  return {std::max(d.n_u, s.n_u), std::max(d.n_v, s.n_v)};
}

// ε_obj = ε_px · d_min / f_px (see the opening comment).
inline double object_tolerance(double pixels, double nearest_depth, double viewport_height_px, double fovy_radians) {
  const double f_px = 0.5 * viewport_height_px / std::tan(0.5 * fovy_radians);
  return pixels * nearest_depth / f_px;
}

}  // namespace frontsteal::tess
