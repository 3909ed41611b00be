// loop_validation.hpp — are a surface's trim loops a valid trimmed region? Checked when a model is loaded.
//
// The region tracer (trim_region.hpp) and the triangulator assume loops that bound a region: an outer loop
// (counter-clockwise) and holes (clockwise) inside it, none inside another, no two loops meeting, no loop
// meeting itself except at consecutive edges, and no edge that turns straight back on the one before (a
// retraced edge). Input that breaks this made the tessellator report thousands of inconsistencies while the
// model loaded fine; now such a model is refused at load with the loops named.
//
// Method: every edge of every loop is a segment; segments are swept in order of their smallest u, and each is
// tested against the active ones (those whose u-range it overlaps) whose v-range it overlaps too — closed
// segments, so touching counts. Cost O(n log n + k) for n segments, k being the pairs that overlap in both
// ranges: about n for loops that are not wildly tangled (a 10⁶-point circle checks in well under a second),
// quadratic only for inputs whose many edges share one u-range and one v-range. Nesting is then one
// point-in-loop test per hole against the outer loop and the other holes, the loops being disjoint.
// Curved segments are judged on their sampled polygons (sample_loop: 16 points per curve segment).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace frontsteal::tess {

struct LoopDefect {
  enum class Kind : std::uint8_t { self_intersection, loops_cross, retraced_edge, hole_outside, nested_hole };
  Kind kind;
  std::size_t loop = 0, other = 0;  // loop indices (other: the second loop, or the same one)
  glm::dvec2 near{0.0};             // a point of the defect
};

inline std::string describe(const LoopDefect& d) {
  switch (d.kind) {
    case LoopDefect::Kind::self_intersection: return "loop intersects itself";
    case LoopDefect::Kind::loops_cross: return "loops cross or touch each other";
    case LoopDefect::Kind::retraced_edge: return "loop retraces an edge (turns straight back)";
    case LoopDefect::Kind::hole_outside: return "hole lies outside the outer loop";
    case LoopDefect::Kind::nested_hole: return "hole lies inside another hole (nested holes are not allowed)";
  }
  return "?";
}

namespace detail {

inline double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Closed segments ab and cd share at least one point.
inline bool segments_meet(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& d) {
  const double d1 = orient(a, b, c), d2 = orient(a, b, d), d3 = orient(c, d, a), d4 = orient(c, d, b);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on = [](const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& r) {
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return (d1 == 0 && on(a, b, c)) || (d2 == 0 && on(a, b, d)) || (d3 == 0 && on(c, d, a)) || (d4 == 0 && on(c, d, b));
}

inline int winding(const std::vector<glm::dvec2>& ring, const glm::dvec2& p) {
  int w = 0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const glm::dvec2& a = ring[k];
    const glm::dvec2& b = ring[(k + 1) % ring.size()];
    if (a.y <= p.y && b.y > p.y && orient(a, b, p) > 0) ++w;
    if (a.y > p.y && b.y <= p.y && orient(a, b, p) < 0) --w;
  }
  return w;
}

}  // namespace detail

// `loops[0]` is the outer loop, the rest are holes; each is a closed polygon (last point not repeated).
// Returns the first defect found, or nothing for a valid region.
inline std::optional<LoopDefect> find_loop_defect(const std::vector<std::vector<glm::dvec2>>& loops) {
  struct Segment {
    glm::dvec2 a, b;
    double u_lo, u_hi, v_lo, v_hi;
    std::uint32_t loop, index;
  };
  std::vector<Segment> segments;
  std::size_t total = 0;
  for (const auto& ring : loops) total += ring.size();
  segments.reserve(total);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& ring = loops[l];
    const std::size_t n = ring.size();
    for (std::size_t k = 0; k < n; ++k) {
      const glm::dvec2 a = ring[k], b = ring[(k + 1) % n];
      if (a == b) continue;  // a repeated point: no edge
      // Consecutive edges meet at their shared vertex; they are a defect only if the second turns straight back.
      const glm::dvec2 c = ring[(k + 2) % n];
      if (n >= 3 && detail::orient(a, b, c) == 0 && glm::dot(b - a, c - b) < 0) {
        return LoopDefect{LoopDefect::Kind::retraced_edge, l, l, b};
      }
      segments.push_back({a, b, std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y),
                          static_cast<std::uint32_t>(l), static_cast<std::uint32_t>(k)});
    }
  }
  std::sort(segments.begin(), segments.end(), [](const Segment& l, const Segment& r) { return l.u_lo < r.u_lo; });
  const auto adjacent = [&](const Segment& s, const Segment& t) {
    if (s.loop != t.loop) return false;
    const std::size_t n = loops[s.loop].size();
    return (s.index + 1) % n == t.index || (t.index + 1) % n == s.index;
  };
  std::vector<std::uint32_t> active;  // indices into segments, whose u-range may still overlap
  for (std::uint32_t k = 0; k < segments.size(); ++k) {
    const Segment& s = segments[k];
    std::erase_if(active, [&](std::uint32_t j) { return segments[j].u_hi < s.u_lo; });
    for (std::uint32_t j : active) {
      const Segment& t = segments[j];
      if (t.v_hi < s.v_lo || s.v_hi < t.v_lo) continue;
      if (adjacent(s, t)) {
        // Consecutive edges share one vertex; anything more (overlap along a line) was caught as retraced,
        // except for a two-edge loop, which encloses nothing and is refused by its area.
        continue;
      }
      if (!detail::segments_meet(s.a, s.b, t.a, t.b)) continue;
      const glm::dvec2 near = 0.5 * (s.a + s.b);
      if (s.loop == t.loop) return LoopDefect{LoopDefect::Kind::self_intersection, s.loop, s.loop, near};
      return LoopDefect{LoopDefect::Kind::loops_cross, std::min(s.loop, t.loop), std::max(s.loop, t.loop), near};
    }
    active.push_back(k);
  }
  // Disjoint loops: one vertex of each hole tells where the whole hole lies. Bounding boxes keep the winding
  // tests to the holes that could contain it (the box tests are quadratic in the number of holes, which is
  // small next to the number of vertices for every model we know).
  std::vector<glm::dvec4> box(loops.size());  // (u_lo, v_lo, u_hi, v_hi)
  for (std::size_t l = 0; l < loops.size(); ++l) {
    box[l] = {1e300, 1e300, -1e300, -1e300};
    for (const glm::dvec2& p : loops[l])
      box[l] = {std::min(box[l].x, p.x), std::min(box[l].y, p.y), std::max(box[l].z, p.x), std::max(box[l].w, p.y)};
  }
  const auto in_box = [&](std::size_t l, const glm::dvec2& p) {
    return box[l].x <= p.x && p.x <= box[l].z && box[l].y <= p.y && p.y <= box[l].w;
  };
  for (std::size_t h = 1; h < loops.size(); ++h) {
    if (loops[h].empty()) continue;
    const glm::dvec2 p = loops[h][0];
    if (!loops[0].empty() && (!in_box(0, p) || detail::winding(loops[0], p) == 0)) {
      return LoopDefect{LoopDefect::Kind::hole_outside, h, 0, p};
    }
    for (std::size_t g = 1; g < loops.size(); ++g) {
      if (g != h && in_box(g, p) && detail::winding(loops[g], p) != 0)
        return LoopDefect{LoopDefect::Kind::nested_hole, h, g, p};
    }
  }
  return std::nullopt;
}

}  // namespace frontsteal::tess
