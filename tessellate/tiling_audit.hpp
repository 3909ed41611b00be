// tiling_audit.hpp — do these triangles tile that polygon exactly? A check that does not trust the triangulator.
//
// Input: a piece of a trimmed cell (outer ring counter-clockwise, holes clockwise, each vertex with an id) and
// triangles given as id triples. The triangles tile the piece exactly — no point covered twice, no hole
// covered, nothing left out — if and only if
//   1. every triangle is counter-clockwise, or degenerate (|2·area| ≤ a tolerance the caller chooses), and
//   2. as 1-chains, the triangles' boundaries add up to the piece's boundary: count each directed edge a→b of
//      every triangle +1 and of every ring −1, count b→a as −1 times a→b's count; every edge must sum to 0.
// Why this is enough: the coverage w(x) = Σ_t [x ∈ t] of counter-clockwise triangles is a 2-chain whose
// boundary is the sum of the triangles' boundaries (2). A compactly supported 2-chain in the plane is fixed by
// its boundary, so w equals the winding number of the piece's rings: 1 inside the piece, 0 in its holes and
// outside. Every term of w is +1 (1), so w = 1 means exactly one triangle covers x. Degenerate triangles have
// no area and only carry edges; they stay in the audit and the caller leaves them out of the mesh.
//
// The test is combinatorial on ids, with no tolerance on positions except for the degenerate area, so it
// cannot be fooled by an overlap that happens to leave the total area right. Cost: one sort of 3t + r edge
// keys per piece (t triangles, r ring vertices); the scratch keeps its capacity, so no steady-state allocation.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "tessellate/polygon_triangulation.hpp"

namespace frontsteal::tess {

enum class TilingVerdict : std::uint8_t {
  exact,              // the triangles tile the piece
  inverted_triangle,  // a clockwise triangle of more than degenerate area: some point is covered −1 times
  boundary_mismatch,  // the triangles' edges do not cancel to the piece's rings: overlap, gap or covered hole
};

inline const char* to_string(TilingVerdict v) {
  switch (v) {
    case TilingVerdict::exact: return "exact";
    case TilingVerdict::inverted_triangle: return "inverted triangle";
    case TilingVerdict::boundary_mismatch: return "boundary mismatch";
  }
  return "?";
}

class TilingAudit {
 public:
  // `position(id)` gives a vertex's (u, v); `degenerate_area2` bounds |2·area| of a triangle that counts as
  // degenerate (rounding on nearly collinear vertices), not inverted.
  template <class PositionOf>
  TilingVerdict check(const PolygonRing& outer, std::span<const PolygonRing> holes,
                      std::span<const std::uint32_t> triangles, PositionOf&& position, double degenerate_area2) {
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
      const double a2 = detail::cross2(position(triangles[t]), position(triangles[t + 1]), position(triangles[t + 2]));
      if (a2 < -degenerate_area2) return TilingVerdict::inverted_triangle;
    }
    edges_.clear();
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
      add(triangles[t], triangles[t + 1], +1);
      add(triangles[t + 1], triangles[t + 2], +1);
      add(triangles[t + 2], triangles[t], +1);
    }
    add_ring(outer);
    for (const PolygonRing& hole : holes) add_ring(hole);
    std::sort(edges_.begin(), edges_.end(), [](const Edge& l, const Edge& r) { return l.key < r.key; });
    for (std::size_t k = 0; k < edges_.size();) {
      int sum = 0;
      const std::uint64_t key = edges_[k].key;
      for (; k < edges_.size() && edges_[k].key == key; ++k) sum += edges_[k].count;
      if (sum != 0) return TilingVerdict::boundary_mismatch;
    }
    return TilingVerdict::exact;
  }

 private:
  struct Edge {
    std::uint64_t key;  // (smaller id, larger id)
    int count;          // +1 for smaller→larger, −1 for the reverse, times the side's sign
  };

  void add(std::uint32_t a, std::uint32_t b, int sign) {
    if (a == b) return;  // a zero-length edge bounds nothing
    const bool forward = a < b;
    const std::uint64_t lo = forward ? a : b, hi = forward ? b : a;
    edges_.push_back({lo << 32 | hi, forward ? sign : -sign});
  }
  void add_ring(const PolygonRing& ring) {
    for (std::size_t k = 0; k < ring.size(); ++k) add(ring[k].id, ring[(k + 1) % ring.size()].id, -1);
  }

  std::vector<Edge> edges_;
};

}  // namespace frontsteal::tess
