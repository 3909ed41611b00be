// polygon_piece.hpp — a triangulator's input for the tests: rings of (u, v) points with ids, and the positions
// behind the ids (for the tiling audit and the coverage probes).
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/polygon_triangulation.hpp"
#include "tessellate/tiling_audit.hpp"
#include "tests/tessellate/coverage_probe.hpp"

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

// Triangles (id triples) over a piece in the unit cell, judged twice: the tiling audit, and 400 random probes of
// coverage against the rings' winding number (coverage_probe.hpp).
struct PieceCheck {
  TilingVerdict verdict;
  CoverageReport coverage;
  std::size_t triangles;
};

inline PieceCheck check_piece(const Piece& piece, std::span<const std::uint32_t> tris, std::mt19937_64& rng) {
  TilingAudit audit;
  const auto position = [&](std::uint32_t id) { return piece.positions[id]; };
  PieceCheck c{audit.check(piece.outer, piece.holes, tris, position, 1e-14), {}, tris.size() / 3};
  std::vector<std::array<glm::dvec2, 3>> corners;
  for (std::size_t t = 0; t < tris.size(); t += 3)
    corners.push_back({position(tris[t]), position(tris[t + 1]), position(tris[t + 2])});
  std::vector<std::vector<glm::dvec2>> rings{ring_points(piece.outer)};
  for (const auto& h : piece.holes) rings.push_back(ring_points(h));
  c.coverage = probe_coverage(corners, rings, {0, 0}, {1, 1}, rng, 400, 1e-9);
  return c;
}

}  // namespace frontsteal::tess::testing
