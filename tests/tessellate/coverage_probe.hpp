// coverage_probe.hpp — an independent check that triangles tile a polygonal region: at random (u, v) points,
// the number of triangles covering the point must equal the winding number of the region's rings there.
// Written apart from the triangulator and from tiling_audit.hpp (winding by signed crossings),
// so a test that uses both checks the audit too. Points too close to a ring edge or a triangle edge to decide
// in floating point are skipped and counted.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

namespace frontsteal::tess::testing {

// Winding number of closed polygon `ring` around p (counter-clockwise loops count +1).
inline int winding_number(const std::vector<glm::dvec2>& ring, glm::dvec2 p) {
  int w = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const glm::dvec2 a = ring[k], b = ring[(k + 1) % ring.size()];
    const double side = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    if (a.y <= p.y && b.y > p.y && side > 0) ++w;
    if (a.y > p.y && b.y <= p.y && side < 0) --w;
  }
  return w;
}

inline double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 d = b - a;
  const double len2 = glm::dot(d, d);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * d));
}

struct CoverageReport {
  int probes = 0, skipped = 0, mismatches = 0;
  glm::dvec2 first_mismatch{-1.0};
  int covered_there = 0, winding_there = 0;
};

// `triangles`: corner triples in (u, v); `rings`: the region's boundary (outer CCW, holes CW), clamped to
// `lo`..`hi` by the caller if needed. Probes are drawn uniformly in the box lo..hi.
inline CoverageReport probe_coverage(const std::vector<std::array<glm::dvec2, 3>>& triangles,
                                     const std::vector<std::vector<glm::dvec2>>& rings, glm::dvec2 lo, glm::dvec2 hi,
                                     std::mt19937_64& rng, int probes, double margin) {
  CoverageReport r;
  std::uniform_real_distribution<double> U(lo.x, hi.x), V(lo.y, hi.y);
  for (int k = 0; k < probes; ++k) {
    const glm::dvec2 p{U(rng), V(rng)};
    bool near = false;
    int winding = 0;
    for (const auto& ring : rings) {
      winding += winding_number(ring, p);
      for (std::size_t e = 0; e < ring.size() && !near; ++e)
        near = distance_to_segment(p, ring[e], ring[(e + 1) % ring.size()]) < margin;
    }
    int covered = 0;
    for (const auto& t : triangles) {
      for (int e = 0; e < 3 && !near; ++e) near = distance_to_segment(p, t[e], t[(e + 1) % 3]) < margin;
      const auto side = [&](glm::dvec2 a, glm::dvec2 b) {
        return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      };
      const double s0 = side(t[0], t[1]), s1 = side(t[1], t[2]), s2 = side(t[2], t[0]);
      if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) ++covered;  // drawn either way round
    }
    if (near) {
      ++r.skipped;
      continue;
    }
    ++r.probes;
    if (covered != winding) {
      if (r.mismatches++ == 0) r.first_mismatch = p, r.covered_there = covered, r.winding_there = winding;
    }
  }
  return r;
}

}  // namespace frontsteal::tess::testing
