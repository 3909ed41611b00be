// The tiling audit (tessellate/tiling_audit.hpp) on hand-made triangulations whose verdict is known: it
// accepts exact tilings (with a degenerate sliver), and rejects an overlap that keeps the total area right,
// a covered hole, a gap and an inverted triangle.
#include "tessellate/tiling_audit.hpp"

#include <catch2/catch.hpp>

namespace ts = frontsteal::tess;

namespace {

// Unit square 0..3 (counter-clockwise), a midpoint 4 on the bottom edge, and a square hole 5..8 (clockwise).
const std::vector<glm::dvec2> kPositions = {{0, 0},     {1, 0},     {1, 1},     {0, 1},    {0.5, 0},
                                            {0.4, 0.4}, {0.4, 0.6}, {0.6, 0.6}, {0.6, 0.4}};

ts::PolygonRing ring(std::initializer_list<std::uint32_t> ids) {
  ts::PolygonRing r;
  for (std::uint32_t id : ids) r.push_back({kPositions[id], id});
  return r;
}

ts::TilingVerdict audit(const ts::PolygonRing& outer, const std::vector<ts::PolygonRing>& holes,
                        const std::vector<std::uint32_t>& triangles) {
  ts::TilingAudit a;
  return a.check(
      outer, holes, triangles, [](std::uint32_t id) { return kPositions[id]; }, 1e-14);
}

}  // namespace

TEST_CASE("exact tilings pass, a degenerate sliver included", "[tiling]") {
  CHECK(audit(ring({0, 1, 2, 3}), {}, {0, 1, 2, 0, 2, 3}) == ts::TilingVerdict::exact);
  CHECK(audit(ring({0, 1, 2, 3}), {}, {0, 1, 3, 1, 2, 3}) == ts::TilingVerdict::exact);
  // 0, 4, 1 are collinear: the sliver (0, 4, 1) carries the edges 0→4→1 and has no area.
  CHECK(audit(ring({0, 4, 1, 2, 3}), {}, {0, 4, 1, 0, 1, 2, 0, 2, 3}) == ts::TilingVerdict::exact);
  // The square with its hole, by eight triangles around the hole.
  const std::vector<std::uint32_t> around = {0, 1, 8, 0, 8, 5, 1, 2, 7, 1, 7, 8, 2, 3, 6, 2, 6, 7, 3, 0, 5, 3, 5, 6};
  CHECK(audit(ring({0, 1, 2, 3}), {ring({5, 6, 7, 8})}, around) == ts::TilingVerdict::exact);
}

TEST_CASE("negative controls: overlap with the right area, covered hole, gap, inverted triangle", "[tiling]") {
  // Twice the same half: area 1, like the square, but half of it is covered twice and half not at all.
  CHECK(audit(ring({0, 1, 2, 3}), {}, {0, 1, 2, 0, 1, 2}) == ts::TilingVerdict::boundary_mismatch);
  // The square triangulated as if it had no hole.
  CHECK(audit(ring({0, 1, 2, 3}), {ring({5, 6, 7, 8})}, {0, 1, 2, 0, 2, 3}) == ts::TilingVerdict::boundary_mismatch);
  // One triangle missing.
  CHECK(audit(ring({0, 1, 2, 3}), {}, {0, 1, 2}) == ts::TilingVerdict::boundary_mismatch);
  // A clockwise triangle: its edges can still cancel (a fold), the orientation test catches it.
  CHECK(audit(ring({0, 1, 2, 3}), {}, {0, 1, 2, 0, 2, 3, 0, 2, 1, 0, 1, 2}) == ts::TilingVerdict::inverted_triangle);
  // The wrong orientation of the boundary itself.
  CHECK(audit(ring({0, 3, 2, 1}), {}, {0, 1, 2, 0, 2, 3}) == ts::TilingVerdict::boundary_mismatch);
}
