// polygon_piece.hpp — a triangulator's input for the tests: rings of (u, v) points with ids, and the positions
// behind the ids (for the tiling audit and the coverage probes).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/polygon_triangulation.hpp"

namespace frontsteal::tess::testing {

struct Piece {
  PolygonRing outer;
  std::vector<PolygonRing> holes;
  std::vector<glm::dvec2> positions;  // by id
};

// A ring through `pts`, each point a new id of `piece`.
inline PolygonRing ring_of(Piece& piece, const std::vector<glm::dvec2>& pts) {
  PolygonRing r;
  for (const glm::dvec2& p : pts) {
    r.push_back({p, static_cast<std::uint32_t>(piece.positions.size())});
    piece.positions.push_back(p);
  }
  return r;
}

inline std::vector<glm::dvec2> ring_points(const PolygonRing& ring) {
  std::vector<glm::dvec2> p;
  for (const PolygonVertex& v : ring) p.push_back(v.uv);
  return p;
}

}  // namespace frontsteal::tess::testing
