// The trimmed region cut along grid lines (tessellate/trim_region.hpp) and the ear clipper
// (polygon_triangulation.hpp): the cells' pieces add up to exactly the trimmed area, stay inside their cells,
// and triangulate to their own area — on random star-shaped loops with holes, on loops through grid corners
// and along grid lines, and on non-uniform grids.
#include "tessellate/trim_region.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <sstream>

#include "tests/tessellate/trim_shapes.hpp"

namespace ts = frontsteal::tess;
using namespace frontsteal::tess::testing;

namespace {

double ring_area(const ts::PolygonRing& r) {
  double a = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const glm::dvec2 p = r[k].uv, q = r[(k + 1) % r.size()].uv;
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

double polygon_area(const ts::Polygon2& r) { return 0.5 * ts::signed_area2(r); }

std::vector<double> uniform_lines(int n) {
  std::vector<double> l(static_cast<std::size_t>(n + 1));
  for (int k = 0; k <= n; ++k) l[k] = static_cast<double>(k) / n;
  return l;
}

struct Totals {
  double area = 0;           // Σ pieces (outer − holes) + full cells
  double triangle_area = 0;  // Σ ear-clipped triangles + full cells
  int negative_triangles = 0;
  double worst_escape = 0;  // how far a piece vertex lies outside its cell
};

Totals cut(const std::vector<ts::Polygon2>& loops, const std::vector<double>& ul, const std::vector<double>& vl,
           int* inconsistencies) {
  ts::GridTrimmer t;
  t.run(loops, ul, vl);
  Totals tot;
  std::vector<std::uint32_t> tris, next, prev;
  for (int i = 0; i < t.cells_u(); ++i) {
    for (int j = 0; j < t.cells_v(); ++j) {
      const double cell = (ul[i + 1] - ul[i]) * (vl[j + 1] - vl[j]);
      if (t.kind(i, j) == ts::CellKind::full) {
        tot.area += cell;
        tot.triangle_area += cell;
      }
      if (t.kind(i, j) != ts::CellKind::partial) continue;
      for (const ts::TracedPiece& piece : t.trace(i, j)) {
        double a = ring_area(piece.outer);
        for (const auto& h : piece.holes) a += ring_area(h);
        tot.area += a;
        const auto escape = [&](const ts::PolygonRing& r) {
          for (const ts::PolygonVertex& v : r) {
            const double e = std::max({ul[i] - v.uv.x, v.uv.x - ul[i + 1], vl[j] - v.uv.y, v.uv.y - vl[j + 1], 0.0});
            tot.worst_escape = std::max(tot.worst_escape, e);
          }
        };
        escape(piece.outer);
        for (const auto& h : piece.holes) escape(h);
        ts::PolygonRing ring = piece.outer;
        std::vector<ts::PolygonRing> holes = piece.holes;
        ts::join_holes(ring, holes);
        tris.clear();
        ts::clip_ears(ring, tris, next, prev);
        for (std::size_t k = 0; k < tris.size(); k += 3) {
          const glm::dvec2 a0 = t.position(tris[k]), b0 = t.position(tris[k + 1]), c0 = t.position(tris[k + 2]);
          const double ta = 0.5 * ts::detail::cross2(a0, b0, c0);
          if (ta < 0) ++tot.negative_triangles;
          tot.triangle_area += ta;
        }
      }
    }
  }
  *inconsistencies = t.inconsistencies();
  return tot;
}

// No two edges of the loops cross (adjacent edges of one loop share an endpoint and are skipped).
bool simple(const std::vector<ts::Polygon2>& loops) {
  std::vector<std::pair<glm::dvec2, glm::dvec2>> edges;
  std::vector<std::pair<double, double>> points;
  for (const auto& l : loops) {
    for (const glm::dvec2& p : l) points.emplace_back(p.x, p.y);
  }
  std::sort(points.begin(), points.end());
  if (std::adjacent_find(points.begin(), points.end()) != points.end()) return false;  // loops touching at a point
  for (const auto& l : loops) {
    for (std::size_t k = 0; k < l.size(); ++k) edges.emplace_back(l[k], l[(k + 1) % l.size()]);
  }
  for (std::size_t a = 0; a < edges.size(); ++a) {
    for (std::size_t b = a + 1; b < edges.size(); ++b) {
      if (ts::detail::segments_cross(edges[a].first, edges[a].second, edges[b].first, edges[b].second)) return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("random star-shaped outer loops with holes: the cells add up to the trimmed area", "[trim]") {
  std::mt19937_64 rng(20261121);
  int valid = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_int_distribution<int> cells(1, 24), verts(3, 40);
    const int nu = cells(rng), nv = cells(rng);
    // At least 8 vertices: the outer loop's chords then stay ≥ 0.3·cos(22.5°) from the centre, around the holes.
    std::vector<ts::Polygon2> loops{random_star(rng, {0.5, 0.5}, 0.3, 0.49, std::max(8, verts(rng)), true)};
    double exact = polygon_area(loops[0]);
    // Up to three holes, each inside a disc that the outer loop contains (the outer's radius is ≥ 0.3).
    const int holes = trial % 4;
    const glm::dvec2 centres[3] = {{0.38, 0.5}, {0.6, 0.42}, {0.6, 0.6}};
    for (int h = 0; h < holes; ++h) {
      loops.push_back(random_star(rng, centres[h], 0.02, 0.08, verts(rng), false));
      exact += polygon_area(loops.back());
    }
    // Snap vertices near a grid line onto it (and near a corner onto the corner): the degenerate cases.
    if (trial % 3 == 0) {
      for (auto& loop : loops) {
        for (glm::dvec2& p : loop) {
          const double su = std::round(p.x * nu) / nu, sv = std::round(p.y * nv) / nv;
          if (std::abs(su - p.x) < 0.01) p.x = su;
          if (std::abs(sv - p.y) < 0.01) p.y = sv;
        }
      }
      if (!simple(loops)) continue;  // snapping made loops cross: not a valid input
      exact = 0;
      for (const auto& loop : loops) exact += polygon_area(loop);
    }
    if (!simple(loops)) continue;
    ++valid;
    int bad = 0;
    const Totals t = cut(loops, uniform_lines(nu), uniform_lines(nv), &bad);
    INFO("trial " << trial << ": " << nu << "x" << nv << " cells, " << loops.size() << " loops, exact area " << exact
                  << ", pieces " << t.area << ", triangles " << t.triangle_area);
    CHECK(bad == 0);
    // Nudging vertices off grid lines moves them by 1e-6 of a cell: the area moves by about that much.
    CHECK(t.area == Approx(exact).margin(1e-5));
    CHECK(t.triangle_area == Approx(exact).margin(1e-5));
    CHECK(t.negative_triangles == 0);
    CHECK(t.worst_escape < 1e-12);
  }
  CHECK(valid > 150);  // snapping rarely makes loops touch or cross; those trials are skipped
}

TEST_CASE("a diamond through grid corners and a square along grid lines", "[trim]") {
  int bad = 0;
  // Diamond with its vertices on grid corners of a 4×4 grid: every crossing is at a corner.
  const ts::Polygon2 diamond{{0.5, 0.0}, {1.0, 0.5}, {0.5, 1.0}, {0.0, 0.5}};
  Totals t = cut({diamond}, uniform_lines(4), uniform_lines(4), &bad);
  CHECK(bad == 0);
  CHECK(t.area == Approx(0.5).margin(1e-5));
  CHECK(t.triangle_area == Approx(0.5).margin(1e-5));
  // A square hole whose sides lie on grid lines, in the whole domain.
  const ts::Polygon2 outer{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const ts::Polygon2 hole{{0.25, 0.25}, {0.25, 0.75}, {0.75, 0.75}, {0.75, 0.25}};
  t = cut({outer, hole}, uniform_lines(4), uniform_lines(4), &bad);
  CHECK(bad == 0);
  CHECK(t.area == Approx(0.75).margin(1e-5));
  CHECK(t.triangle_area == Approx(0.75).margin(1e-5));
  // A hole smaller than one cell: the cell becomes a piece with a hole, triangulated through a bridge.
  const ts::Polygon2 small{{0.41, 0.41}, {0.41, 0.46}, {0.46, 0.46}, {0.46, 0.41}};
  t = cut({outer, small}, uniform_lines(2), uniform_lines(2), &bad);
  CHECK(bad == 0);
  CHECK(t.area == Approx(1.0 - 0.0025).margin(1e-9));
  CHECK(t.triangle_area == Approx(1.0 - 0.0025).margin(1e-9));
}

TEST_CASE("split_region on a non-uniform knot grid gives each cell its own loops", "[trim]") {
  const ts::Polygon2 outer{{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  const ts::Polygon2 hole{{1.2, 0.5}, {0.8, 1.0}, {1.2, 1.5}, {1.6, 1.0}};  // CW diamond
  const std::vector<double> ul{0, 1, 2.5, 3}, vl{0, 0.7, 2};
  const auto covers = ts::split_region({outer, hole}, ul, vl);
  REQUIRE(covers.size() == 6);
  double area = 0;
  int partial = 0;
  for (std::size_t k = 0; k < covers.size(); ++k) {
    const int iu = static_cast<int>(k) / 2, iv = static_cast<int>(k) % 2;
    const double cell = (ul[iu + 1] - ul[iu]) * (vl[iv + 1] - vl[iv]);
    if (covers[k].kind == ts::CellCover::Kind::full) area += cell;
    if (covers[k].kind != ts::CellCover::Kind::partial) continue;
    ++partial;
    for (const auto& piece : covers[k].pieces) {
      CHECK(polygon_area(piece.outer) > 0);
      area += polygon_area(piece.outer);
      for (const auto& h : piece.holes) area += polygon_area(h);
    }
  }
  CHECK(partial == 3);  // the diamond reaches 3 of the 4 cells around (1, 0.7) (at v = 0.7 it spans u 1.04–1.36)
  CHECK(area == Approx(6.0 - 0.4).margin(1e-6));
}

TEST_CASE("negative control: a hole with the wrong orientation is not silently accepted", "[trim]") {
  // A counter-clockwise 'hole' inside a counter-clockwise outer loop: winding 2 inside, a violated contract.
  const ts::Polygon2 outer{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const ts::Polygon2 wrong{{0.3, 0.3}, {0.7, 0.3}, {0.7, 0.7}, {0.3, 0.7}};
  int bad = 0;
  const Totals t = cut({outer, wrong}, uniform_lines(5), uniform_lines(5), &bad);
  // The area then differs from the intended 1 − 0.16: the check above would catch a wrong orientation.
  CHECK(t.area != Approx(0.84).margin(1e-3));
}
