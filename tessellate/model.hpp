// model.hpp — a trimmed-surface model: surfaces made of one rational Bézier patch and its trim loops.
//
// Trim loops live in the patch's (u, v) domain [0,1]² and are closed chains of segments, each a polynomial
// Bézier curve in (u, v) (degree 1..kMaxDegree; a polyline is a chain of degree-1 segments). Material lies on
// the left of a loop's direction: the outer loop runs counter-clockwise, holes clockwise (as in GLU and in
// Kumar & Manocha, CAD 27(7) 1995). A surface without loops is untrimmed (the whole domain). `component` groups
// surfaces whose triangles must be updated together (paper §5.2); -1 means "not yet assigned".
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess {

struct TrimSegment {
  std::vector<glm::dvec2> control;  // degree = control.size() - 1
  int degree() const noexcept { return static_cast<int>(control.size()) - 1; }
};

struct TrimLoop {
  std::vector<TrimSegment> segments;
};

struct Surface {
  std::string name;
  BezierPatch patch;
  std::vector<TrimLoop> loops;  // first loop outer (CCW); the rest holes (CW)
  int component = -1;
  // Part of a closed, outward-oriented solid (S_u × S_v points out): its back faces may be culled.
  bool solid = false;
};

struct Model {
  std::string name;
  std::vector<Surface> surfaces;
};

// A loop as a closed polygon: each segment sampled at `samples_per_segment` points (its end omitted, being
// the next segment's start). Used for orientation and self-intersection checks and for tests.
inline std::vector<glm::dvec2> sample_loop(const TrimLoop& loop, int samples_per_segment = 16) {
  std::vector<glm::dvec2> out;
  for (const TrimSegment& seg : loop.segments) {
    const int d = seg.degree();
    const int samples = d == 1 ? 1 : samples_per_segment;
    for (int k = 0; k < samples; ++k) {
      const double t = static_cast<double>(k) / samples;
      // de Casteljau in 2D
      std::vector<glm::dvec2> c = seg.control;
      for (int r = 1; r <= d; ++r) {
        for (int i = 0; i + r <= d; ++i) c[i] = (1 - t) * c[i] + t * c[i + 1];
      }
      out.push_back(c[0]);
    }
  }
  return out;
}

// Twice the signed area of a closed polygon (positive: counter-clockwise).
inline double signed_area2(const std::vector<glm::dvec2>& poly) {
  double a = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec2& p = poly[i];
    const glm::dvec2& q = poly[(i + 1) % poly.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return a;
}

}  // namespace frontsteal::tess
