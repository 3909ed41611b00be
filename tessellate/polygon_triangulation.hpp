// polygon_triangulation.hpp — triangulating a small polygon with holes in the (u, v) domain.
//
// Used for the trimmed cells of a patch's grid (trim_region.hpp): a cell cut by trim curves becomes one or
// more pieces, each an outer boundary (counter-clockwise) with holes (clockwise). Pieces are small — a cell's
// corners plus the trim points inside the cell — so the classic O(n²) ear clipping is the right tool:
//   1. Holes are joined to the outer boundary by bridges (Eberly, "Triangulation by ear clipping", 2002):
//      holes in decreasing order of their largest u; from a hole's rightmost vertex M, the bridge goes to the
//      nearest vertex V (outer boundary or already-joined holes) such that the segment MV crosses no edge. The
//      polygon then runs …V, M, (around the hole), M, V… — weakly simple, still counter-clockwise.
//      Once a hole is joined, V occurs twice in the ring (three times after a second bridge to it, …), and
//      each copy owns a different sector of the angle at V. The bridge must leave from the copy whose sector
//      contains the direction V→M; splicing it at another copy makes the ring cross itself at V, and ear
//      clipping then covers holes and overlaps itself (the wave-1 defect: cells with three or more holes).
//   2. Ears are clipped: a convex vertex whose triangle contains no other (non-coincident) vertex. If floating
//      point leaves no strict ear (nearly collinear chains), the most convex vertex is clipped, so the routine
//      always terminates with n − 2 triangles for n vertices.
// Every clipped triangle is emitted, degenerate ones (zero or rounding-negative area) included, so that the
// triangles' edges always cancel to the ring's boundary; the caller audits the result (tiling_audit.hpp) and
// drops the degenerate ones. Vertices carry an opaque id (the caller's vertex index) so the output is a list
// of id triples, counter-clockwise in (u, v). Scratch vectors are passed in and keep their capacity.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace frontsteal::tess {

struct PolygonVertex {
  glm::dvec2 uv;
  std::uint32_t id;
};

using PolygonRing = std::vector<PolygonVertex>;

namespace detail {

inline double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Proper or touching intersection of segments ab and cd, excluding shared endpoints.
inline bool segments_cross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& d) {
  if (a == c || a == d || b == c || b == d) return false;
  const double d1 = cross2(a, b, c), d2 = cross2(a, b, d), d3 = cross2(c, d, a), d4 = cross2(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r, double cr) {
    return cr == 0 && std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

// Is direction d, leaving the ring's vertex v, inside the sector of the polygon at v? The ring runs
// counter-clockwise with the material on its left, so the sector is swept counter-clockwise from the outgoing
// edge (to `next`) to the incoming one (back to `prev`); a reflex vertex's sector is wider than a half-turn.
inline bool in_sector(const glm::dvec2& prev, const glm::dvec2& v, const glm::dvec2& next, const glm::dvec2& d) {
  const glm::dvec2 out = next - v, back = prev - v;
  const auto cross = [](const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; };
  if (cross(out, back) > 0) return cross(out, d) > 0 && cross(d, back) > 0;
  return cross(out, d) > 0 || cross(d, back) > 0;
}

inline bool in_triangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

}  // namespace detail

// Which copy of a repeated bridge end the bridge leaves from (step 1). `sector` is the rule; `first_copy` is the
// wave-1 defect, kept only so the negative controls can plant it and show that the tiling audit catches it.
enum class BridgeCopy : std::uint8_t { sector, first_copy };

// Splices each hole into `outer` with a bridge (step 1 above). `outer` is modified in place, `holes` reordered.
inline void join_holes(PolygonRing& outer, std::span<PolygonRing> holes, BridgeCopy copy = BridgeCopy::sector) {
  std::sort(holes.begin(), holes.end(), [](const PolygonRing& a, const PolygonRing& b) {
    const auto max_u = [](const PolygonRing& r) {
      double m = -std::numeric_limits<double>::infinity();
      for (const PolygonVertex& v : r) m = std::max(m, v.uv.x);
      return m;
    };
    return max_u(a) > max_u(b);
  });
  thread_local PolygonRing merged;  // swapped with `outer` below: both keep their capacity
  for (std::size_t h = 0; h < holes.size(); ++h) {
    const PolygonRing& hole = holes[h];
    if (hole.size() < 3) continue;
    std::size_t m = 0;
    for (std::size_t k = 1; k < hole.size(); ++k) {
      if (hole[k].uv.x > hole[m].uv.x) m = k;
    }
    const glm::dvec2 mp = hole[m].uv;
    // Every edge that a bridge must not cross: the current outer ring and all holes not yet joined.
    const auto crosses_any = [&](const glm::dvec2& a, const glm::dvec2& b) {
      for (std::size_t k = 0; k < outer.size(); ++k) {
        if (detail::segments_cross(a, b, outer[k].uv, outer[(k + 1) % outer.size()].uv)) return true;
      }
      for (std::size_t g = h; g < holes.size(); ++g) {
        const PolygonRing& r = holes[g];
        for (std::size_t k = 0; k < r.size(); ++k) {
          if (detail::segments_cross(a, b, r[k].uv, r[(k + 1) % r.size()].uv)) return true;
        }
      }
      return false;
    };
    // The nearest visible vertex (the first in ring order among equally near ones), preferring vertices to the
    // right (the classic ray direction), then any. Candidates are tried nearest first, so the visibility test
    // (every edge, each time) usually runs once or twice instead of once per nearer vertex met in ring order.
    std::size_t best = outer.size();
    thread_local std::vector<std::pair<double, std::size_t>> candidates;  // keeps its capacity
    for (int pass = 0; pass < 2 && best == outer.size(); ++pass) {
      candidates.clear();
      for (std::size_t k = 0; k < outer.size(); ++k) {
        const glm::dvec2 d = outer[k].uv - mp;
        if ((pass == 0 && d.x < 0) || outer[k].uv == mp) continue;
        candidates.emplace_back(glm::dot(d, d), k);
      }
      std::sort(candidates.begin(), candidates.end());
      for (const auto& [dist, k] : candidates) {
        if (!crosses_any(mp, outer[k].uv)) {
          best = k;
          break;
        }
      }
    }
    if (best == outer.size()) best = 0;  // degenerate input: join anyway; ear clipping still terminates
    if (copy == BridgeCopy::sector) {
      const std::size_t n = outer.size();
      for (std::size_t k = 0; k < n; ++k) {
        if (outer[k].uv != outer[best].uv) continue;
        if (detail::in_sector(outer[(k + n - 1) % n].uv, outer[k].uv, outer[(k + 1) % n].uv, mp - outer[k].uv)) {
          best = k;
          break;
        }
      }
    }
    merged.clear();
    merged.insert(merged.end(), outer.begin(), outer.begin() + static_cast<std::ptrdiff_t>(best) + 1);
    for (std::size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(m + k) % hole.size()]);
    merged.push_back(outer[best]);
    merged.insert(merged.end(), outer.begin() + static_cast<std::ptrdiff_t>(best) + 1, outer.end());
    outer.swap(merged);
  }
}

// Ear clipping (step 2 above) of a counter-clockwise ring; appends its n − 2 id triples to `triangles`.
inline void clip_ears(const PolygonRing& ring, std::vector<std::uint32_t>& triangles, std::vector<std::uint32_t>& next,
                      std::vector<std::uint32_t>& prev) {
  const std::size_t n = ring.size();
  if (n < 3) return;
  next.resize(n);
  prev.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    next[k] = static_cast<std::uint32_t>((k + 1) % n);
    prev[k] = static_cast<std::uint32_t>((k + n - 1) % n);
  }
  std::size_t remaining = n;
  std::uint32_t cursor = 0;
  const auto is_ear = [&](std::uint32_t b) {
    const std::uint32_t a = prev[b], c = next[b];
    const glm::dvec2 &pa = ring[a].uv, &pb = ring[b].uv, &pc = ring[c].uv;
    if (detail::cross2(pa, pb, pc) <= 0) return false;
    // A vertex outside the triangle's bounding box is outside the triangle: most are rejected by four
    // comparisons before in_triangle's three cross products. The answers differ only where in_triangle's own
    // was an accident of rounding (a point beyond the box yet within a few ulps of a corner); the frame's
    // triangles came out byte-identical with and without the box (frame_benchmark --frame-digest).
    const double lo_u = std::min({pa.x, pb.x, pc.x}), hi_u = std::max({pa.x, pb.x, pc.x});
    const double lo_v = std::min({pa.y, pb.y, pc.y}), hi_v = std::max({pa.y, pb.y, pc.y});
    for (std::uint32_t k = next[c]; k != a; k = next[k]) {
      const glm::dvec2& p = ring[k].uv;
      if (p.x < lo_u || p.x > hi_u || p.y < lo_v || p.y > hi_v) continue;
      if (p == pa || p == pb || p == pc) continue;  // bridge duplicates
      if (detail::in_triangle(p, pa, pb, pc)) return false;
    }
    return true;
  };
  while (remaining > 3) {
    std::uint32_t found = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t k = cursor;
    for (std::size_t scanned = 0; scanned < remaining; ++scanned, k = next[k]) {
      if (is_ear(k)) {
        found = k;
        break;
      }
    }
    if (found == std::numeric_limits<std::uint32_t>::max()) {
      // No strict ear (floating point on nearly collinear chains): clip the most convex vertex.
      double best = -std::numeric_limits<double>::infinity();
      k = cursor;
      for (std::size_t scanned = 0; scanned < remaining; ++scanned, k = next[k]) {
        const double c = detail::cross2(ring[prev[k]].uv, ring[k].uv, ring[next[k]].uv);
        if (c > best) best = c, found = k;
      }
    }
    const std::uint32_t a = prev[found], c = next[found];
    triangles.insert(triangles.end(), {ring[a].id, ring[found].id, ring[c].id});
    next[a] = c;
    prev[c] = a;
    cursor = c;
    --remaining;
  }
  const std::uint32_t a = prev[cursor], c = next[cursor];
  triangles.insert(triangles.end(), {ring[a].id, ring[cursor].id, ring[c].id});
}

}  // namespace frontsteal::tess
