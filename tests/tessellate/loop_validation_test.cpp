// Trim-loop validation (tessellate/loop_validation.hpp): valid regions pass — many holes, curves, a 10⁶-point
// loop — and every kind of invalid one is named: self-intersection, loops that cross or touch, a retraced
// edge, a hole outside the outer loop, a hole inside a hole. The parser refuses them with file:line
// (model_format_test.cpp); here the checker itself, including the planted defects it must find.
#include "tessellate/loop_validation.hpp"

#include <catch2/catch.hpp>

#include <numbers>

namespace ts = frontsteal::tess;
using Ring = std::vector<glm::dvec2>;
using Kind = ts::LoopDefect::Kind;

namespace {

Ring square(glm::dvec2 lo, glm::dvec2 hi, bool ccw) {
  Ring r = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  if (!ccw) std::reverse(r.begin(), r.end());
  return r;
}

Ring circle(glm::dvec2 c, double radius, int n, bool ccw) {
  Ring r;
  for (int k = 0; k < n; ++k) {
    const double a = (ccw ? 2 : -2) * std::numbers::pi * k / n;
    r.push_back(c + radius * glm::dvec2(std::cos(a), std::sin(a)));
  }
  return r;
}

std::optional<Kind> kind_of(const std::vector<Ring>& loops) {
  const auto d = ts::find_loop_defect(loops);
  return d ? std::optional<Kind>(d->kind) : std::nullopt;
}

}  // namespace

TEST_CASE("valid regions pass: holes in a grid, circles, a 10^6-point loop", "[loops]") {
  std::vector<Ring> plate = {square({0, 0}, {1, 1}, true)};
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) plate.push_back(circle({0.025 + 0.05 * i, 0.025 + 0.05 * j}, 0.02, 12, false));
  }
  CHECK_FALSE(kind_of(plate).has_value());
  CHECK_FALSE(kind_of({circle({0.5, 0.5}, 0.49, 1'000'000, true)}).has_value());
  // A hole that shares no point with the outer loop but comes within 1e-12 of it.
  CHECK_FALSE(kind_of({square({0, 0}, {1, 1}, true), square({0.5, 1e-12}, {0.6, 0.1}, false)}).has_value());
}

TEST_CASE("negative controls: each defect is found and named", "[loops]") {
  const Ring outer = square({0, 0}, {1, 1}, true);
  // A bow tie.
  CHECK(kind_of({{{0, 0}, {1, 1}, {1, 0}, {0, 1}}}) == Kind::self_intersection);
  // Two holes that cross.
  CHECK(kind_of({outer, square({0.2, 0.2}, {0.5, 0.5}, false), square({0.4, 0.4}, {0.7, 0.7}, false)}) ==
        Kind::loops_cross);
  // A hole that crosses the outer loop.
  CHECK(kind_of({outer, square({0.8, 0.2}, {1.2, 0.5}, false)}) == Kind::loops_cross);
  // Two holes touching at a corner, and a hole touching the outer loop along an edge.
  CHECK(kind_of({outer, square({0.2, 0.2}, {0.4, 0.4}, false), square({0.4, 0.4}, {0.6, 0.6}, false)}) ==
        Kind::loops_cross);
  CHECK(kind_of({outer, square({0.2, 0.0}, {0.4, 0.4}, false)}) == Kind::loops_cross);
  // A spike: the outer loop runs in to (0.5, 0.5) and straight back.
  CHECK(kind_of({{{0, 0}, {0.5, 0}, {0.5, 0.5}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}}}) == Kind::retraced_edge);
  // A hole outside the outer loop, and a hole inside a hole.
  CHECK(kind_of({square({0, 0}, {0.5, 0.5}, true), square({0.6, 0.6}, {0.7, 0.7}, false)}) == Kind::hole_outside);
  CHECK(kind_of({outer, square({0.2, 0.2}, {0.8, 0.8}, false), square({0.4, 0.4}, {0.5, 0.5}, false)}) ==
        Kind::nested_hole);
  // The 10^6-point circle with its top point pulled down across the bottom.
  Ring big = circle({0.5, 0.5}, 0.49, 1'000'000, true);
  big[250'000] = {0.5, 0.001};  // from the top (angle π/2) down past the bottom (v = 0.01)
  CHECK(kind_of({big}) == Kind::self_intersection);
}
