// The constrained triangulation of large pieces (tessellate/constrained_triangulation.hpp), checked by
// what does not trust it: the tiling audit (tessellate/tiling_audit.hpp), random point probes against the
// rings' winding number (tests/tessellate/coverage_probe.hpp) and the triangle count n + 2h − 2 of a polygon
// with holes. Pieces it must refuse come back untouched, and then ear clipping takes them. Fixed seeds.
#include "tessellate/constrained_triangulation.hpp"

#include <catch2/catch.hpp>

#include <numbers>
#include <random>

#include "tessellate/tiling_audit.hpp"
#include "tests/tessellate/coverage_probe.hpp"
#include "tests/tessellate/polygon_piece.hpp"
#include "tests/tessellate/trim_shapes.hpp"

namespace ts = frontsteal::tess;
using namespace frontsteal::tess::testing;

namespace {

std::vector<glm::dvec2> circle_points(glm::dvec2 c, double r, int n, bool ccw) {
  std::vector<glm::dvec2> pts;
  for (int k = 0; k < n; ++k) {
    const double a = (ccw ? 2 : -2) * std::numbers::pi * k / n;
    pts.push_back(c + r * glm::dvec2(std::cos(a), std::sin(a)));
  }
  return pts;
}

// A dense star (a long trim polyline in one cell) with up to `holes` dense circular holes, disjoint.
Piece dense_piece(std::mt19937_64& rng, int outer_vertices, int holes) {
  Piece piece;
  piece.outer = ring_of(piece, random_star(rng, {0.5, 0.5}, 0.3, 0.49, outer_vertices, true));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> sides(24, 300);
  std::vector<glm::dvec3> placed;
  for (int tries = 0; static_cast<int>(piece.holes.size()) < holes && tries < 10000; ++tries) {
    const glm::dvec2 c{0.3 + 0.4 * unit(rng), 0.3 + 0.4 * unit(rng)};
    const double r = 0.01 + 0.05 * unit(rng);
    if (glm::length(c - glm::dvec2(0.5)) + r > 0.29) continue;  // inside the star's smallest radius
    bool clear = true;
    for (const glm::dvec3& o : placed) clear = clear && glm::length(glm::dvec2(o) - c) > r + o.z + 0.002;
    if (!clear) continue;
    placed.push_back({c.x, c.y, r});
    piece.holes.push_back(ring_of(piece, circle_points(c, r, sides(rng), false)));
  }
  return piece;
}

struct Outcome : PieceCheck {
  bool accepted = false;
};

Outcome triangulate_and_check(const Piece& piece, std::mt19937_64& rng, bool drop_first = false) {
  std::vector<std::uint32_t> tris;
  Outcome o;
  o.accepted = ts::triangulate_constrained(piece.outer, piece.holes, tris);
  if (drop_first && tris.size() >= 3) tris.erase(tris.begin(), tris.begin() + 3);
  static_cast<PieceCheck&>(o) = check_piece(piece, tris, rng);
  return o;
}

}  // namespace

TEST_CASE("large pieces with holes are tiled exactly: audit, probes and the triangle count agree", "[triangulation]") {
  std::mt19937_64 rng(20261127);
  for (int trial = 0; trial < 60; ++trial) {
    const int outer_vertices = 384 + static_cast<int>(rng() % 3000);
    const Piece piece = dense_piece(rng, outer_vertices, trial % 7);
    std::size_t vertices = piece.outer.size();
    for (const auto& h : piece.holes) vertices += h.size();
    const Outcome o = triangulate_and_check(piece, rng);
    INFO("trial " << trial << ": " << vertices << " vertices, " << piece.holes.size() << " holes, " << o.triangles
                  << " triangles, audit " << ts::to_string(o.verdict) << ", probe mismatches "
                  << o.coverage.mismatches);
    REQUIRE(o.accepted);
    CHECK(o.verdict == ts::TilingVerdict::exact);
    CHECK(o.coverage.mismatches == 0);
    CHECK(o.triangles == vertices + 2 * piece.holes.size() - 2);
  }
}

TEST_CASE("holes touching each other or the outer ring at a shared vertex need no special case", "[triangulation]") {
  std::mt19937_64 rng(3);
  Piece piece;
  piece.outer = ring_of(piece, circle_points({0.5, 0.5}, 0.45, 200, true));
  // Two holes meeting at one vertex (the same id in both), a third touching the outer ring at its vertex 0.
  piece.holes.push_back(ring_of(piece, circle_points({0.4, 0.5}, 0.1, 60, false)));
  ts::PolygonRing second = ring_of(piece, circle_points({0.6, 0.5}, 0.1, 60, false));
  second[30] = piece.holes[0][0];  // (0.5, 0.5): the first hole's vertex 0 is the second's vertex 30
  piece.holes.push_back(second);
  // A circle of radius 0.05 about (0.9, 0.5) touches the outer circle at (0.95, 0.5): its vertex 0 is the
  // outer ring's vertex 0 (same id).
  ts::PolygonRing third = ring_of(piece, circle_points({0.9, 0.5}, 0.05, 40, false));
  third[0] = piece.outer[0];
  piece.holes.push_back(third);
  const Outcome o = triangulate_and_check(piece, rng);
  INFO(o.triangles << " triangles, audit " << ts::to_string(o.verdict) << ", probe mismatches "
                   << o.coverage.mismatches);
  REQUIRE(o.accepted);
  CHECK(o.verdict == ts::TilingVerdict::exact);
  CHECK(o.coverage.mismatches == 0);
}

TEST_CASE("pieces that need a vertex without an id are refused and left untouched", "[triangulation]") {
  const std::vector<std::uint32_t> before{7, 8, 9};
  const auto refused = [&](const Piece& piece) {
    std::vector<std::uint32_t> tris = before;
    return !ts::triangulate_constrained(piece.outer, piece.holes, tris) && tris == before;
  };
  SECTION("two ids at one (u, v)") {
    Piece piece;
    piece.outer = ring_of(piece, circle_points({0.5, 0.5}, 0.45, 120, true));
    ts::PolygonRing hole = ring_of(piece, circle_points({0.5, 0.5}, 0.1, 40, false));
    hole.push_back({piece.outer[0].uv, static_cast<std::uint32_t>(piece.positions.size())});  // a second id there
    piece.positions.push_back(piece.outer[0].uv);
    piece.holes.push_back(hole);
    CHECK(refused(piece));
  }
  SECTION("a ring crossing itself") {
    Piece piece;
    std::vector<glm::dvec2> pts = circle_points({0.5, 0.5}, 0.45, 120, true);
    std::swap(pts[10], pts[70]);  // two chords across the circle
    piece.outer = ring_of(piece, pts);
    CHECK(refused(piece));
  }
  SECTION("a hole's vertex on the outer ring's edge") {
    Piece piece;
    std::vector<glm::dvec2> outer{{0, 0}, {1, 0}};
    for (const glm::dvec2& p : circle_points({0.5, 0.5}, 0.5, 200, true)) {
      if (p.y > 0.55) outer.push_back(p);  // the top of a circle: the ring is an arch on the segment (0,0)–(1,0)
    }
    piece.outer = ring_of(piece, outer);
    piece.holes.push_back(ring_of(piece, {{0.5, 0.0}, {0.45, 0.1}, {0.55, 0.1}}));  // (0.5, 0) on the base
    CHECK(refused(piece));
  }
}

TEST_CASE("negative control: a dropped triangle is caught by the audit and the probes", "[triangulation]") {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Piece piece = dense_piece(rng, 200 + 50 * trial, trial % 4);
    const Outcome o = triangulate_and_check(piece, rng, true);
    INFO("trial " << trial);
    REQUIRE(o.accepted);
    CHECK(o.verdict == ts::TilingVerdict::boundary_mismatch);
  }
}
