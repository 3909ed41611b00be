// trim_shapes.hpp — trim loops and flat test patches shared by the trimming tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "tessellate/model.hpp"

namespace frontsteal::tess::testing {

// A circle of radius r about c as four cubic Bézier arcs (handle length 0.5523 r), counter-clockwise or not.
inline TrimLoop circle_loop(glm::dvec2 c, double r, bool counter_clockwise) {
  const double k = 0.5522847498307936 * r;
  TrimLoop loop;
  for (int q = 0; q < 4; ++q) {
    const double a0 = q * 0.5 * std::numbers::pi, a1 = (q + 1) * 0.5 * std::numbers::pi;
    const glm::dvec2 p0 = c + r * glm::dvec2(std::cos(a0), std::sin(a0));
    const glm::dvec2 p3 = c + r * glm::dvec2(std::cos(a1), std::sin(a1));
    const glm::dvec2 t0 = glm::dvec2(-std::sin(a0), std::cos(a0));
    const glm::dvec2 t1 = glm::dvec2(-std::sin(a1), std::cos(a1));
    loop.segments.push_back({{p0, p0 + k * t0, p3 - k * t1, p3}});
  }
  if (!counter_clockwise) {
    std::vector<TrimSegment> reversed;
    for (auto it = loop.segments.rbegin(); it != loop.segments.rend(); ++it) {
      TrimSegment s = *it;
      std::reverse(s.control.begin(), s.control.end());
      reversed.push_back(s);
    }
    loop.segments = reversed;
  }
  // Close exactly (the last end equals the first start up to rounding).
  loop.segments.back().control.back() = loop.segments.front().control.front();
  return loop;
}

inline TrimLoop polyline_loop(const std::vector<glm::dvec2>& pts) {
  TrimLoop loop;
  for (std::size_t k = 0; k < pts.size(); ++k) loop.segments.push_back({{pts[k], pts[(k + 1) % pts.size()]}});
  return loop;
}

// A star-shaped polygon about c: random radii in [r_lo, r_hi] at n increasing angles; CCW, or CW when reversed.
inline std::vector<glm::dvec2> random_star(std::mt19937_64& rng, glm::dvec2 c, double r_lo, double r_hi, int n,
                                           bool ccw) {
  std::uniform_real_distribution<double> radius(r_lo, r_hi);
  std::vector<glm::dvec2> pts;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    const double r = radius(rng);
    pts.push_back(c + r * glm::dvec2(std::cos(a), std::sin(a)));
  }
  if (!ccw) std::reverse(pts.begin(), pts.end());
  return pts;
}

// Exact area of a loop of polynomial Bézier segments by Green's theorem, ½∮(u dv − v du), integrated with
// Gauss–Legendre (5 points: exact for the degree ≤ 2·3 − 1 integrands of cubic segments, and close beyond).
inline double loop_area(const TrimLoop& loop) {
  static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                              0.2369268850561891};
  double a = 0;
  for (const TrimSegment& seg : loop.segments) {
    const int d = seg.degree();
    for (int k = 0; k < 5; ++k) {
      const double t = 0.5 * (x[k] + 1);
      // Point and derivative by de Casteljau.
      std::vector<glm::dvec2> c = seg.control;
      for (int r = 1; r < d; ++r) {
        for (int i = 0; i + r <= d; ++i) c[i] = (1 - t) * c[i] + t * c[i + 1];
      }
      const glm::dvec2 deriv = static_cast<double>(d) * (c[1] - c[0]);
      const glm::dvec2 p = (1 - t) * c[0] + t * c[1];
      a += 0.5 * w[k] * 0.5 * (p.x * deriv.y - p.y * deriv.x);
    }
  }
  return a;
}

// A flat unit plate: the bilinear patch (u, v) ↦ (u·size, v·size, 0).
inline BezierPatch flat_plate(double size) {
  BezierPatch p(1, 1);
  p.set(0, 0, {0, 0, 0});
  p.set(1, 0, {size, 0, 0});
  p.set(0, 1, {0, size, 0});
  p.set(1, 1, {size, size, 0});
  return p;
}

}  // namespace frontsteal::tess::testing
