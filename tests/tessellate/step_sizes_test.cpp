// Step sizes and the untrimmed grid (tessellate/step_sizes.hpp, grid_tessellator.hpp): the deviation between
// surface and triangles stays within the tolerance; a negative control shows the check can fail.
#include "tessellate/step_sizes.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "tests/tessellate/random_patch.hpp"
#include <sstream>

#include "tessellate/grid_tessellator.hpp"

namespace ts = frontsteal::tess;
using frontsteal::tess::testing::random_patch;

namespace {

struct Worst {
  double deviation = 0;
  double u = 0, v = 0;
};

// Largest distance, over `samples` random parameters, between S(u,v) and the triangle containing (u,v)
// interpolated linearly at the same parameter (an upper bound on the distance to the nearest triangle point).
Worst worst_deviation(const ts::BezierPatch& p, ts::StepSizes steps, std::mt19937_64& rng, int samples) {
  ts::TriangleBuffers tri;
  std::vector<ts::BernsteinTable> scratch;
  ts::tessellate_untrimmed(p, steps, tri, scratch);
  std::uniform_real_distribution<double> param(0.0, 1.0);
  const auto vertex = [&](int i, int j) { return glm::dvec3(tri.positions[i * (steps.n_v + 1) + j]); };
  Worst w;
  for (int s = 0; s < samples; ++s) {
    const double u = param(rng), v = param(rng);
    const int i = std::min(static_cast<int>(u * steps.n_u), steps.n_u - 1);
    const int j = std::min(static_cast<int>(v * steps.n_v), steps.n_v - 1);
    const double a = u * steps.n_u - i, b = v * steps.n_v - j;
    const glm::dvec3 linear =
        a >= b ? vertex(i, j) + a * (vertex(i + 1, j) - vertex(i, j)) + b * (vertex(i + 1, j + 1) - vertex(i + 1, j))
               : vertex(i, j) + b * (vertex(i, j + 1) - vertex(i, j)) + a * (vertex(i + 1, j + 1) - vertex(i, j + 1));
    const double d = glm::length(ts::evaluate(p, u, v).position - linear);
    if (d > w.deviation) w = {d, u, v};
  }
  return w;
}

// y = x² over x ∈ [0,1], extruded along z: the chord deviation of a parabola is exactly δ²|S''|/8, so the
// deviation bound is tight here.
ts::BezierPatch parabolic_cylinder() {
  ts::BezierPatch p(2, 1);
  for (int j = 0; j <= 1; ++j) {
    p.set(0, j, {0, 0, j});
    p.set(1, j, {0.5, 0, j});
    p.set(2, j, {1, 1, j});
  }
  return p;
}

std::string describe(const ts::BezierPatch& p, ts::StepSizes s, const Worst& w, double eps) {
  std::ostringstream out;
  out << "patch " << p.degree_u << "x" << p.degree_v << " steps " << s.n_u << "x" << s.n_v << " tolerance " << eps
      << ": deviation " << w.deviation << " at (u,v) = (" << w.u << ", " << w.v << ")";
  return out.str();
}

}  // namespace

TEST_CASE("triangles stay within the tolerance of random patches", "[tessellate][steps]") {
  std::mt19937_64 rng(42);
  // Degrees 1..5, then the high degrees imported CAD faces have (8..11, and the largest).
  for (int trial = 0; trial < 128; ++trial) {
    const int du = trial < 120 ? 1 + trial % 5 : (trial < 126 ? 8 + trial % 4 : ts::kMaxDegree);
    const int dv = trial < 120 ? 1 + (trial / 5) % 5 : (trial < 126 ? 2 + trial % 10 : 1 + (trial % 2) * 24);
    const ts::BezierPatch p = random_patch(rng, du, dv, trial % 4 == 3);
    for (double eps : {0.05, 0.005}) {
      const ts::StepSizes s = ts::deviation_steps(ts::net_bounds(p), eps);
      const Worst w = worst_deviation(p, s, rng, 400);
      INFO("trial " << trial << ": " << describe(p, s, w, eps));
      CHECK(w.deviation <= eps);
    }
  }
}

TEST_CASE("the rational quarter cylinder stays within the tolerance", "[tessellate][steps]") {
  ts::BezierPatch p(2, 1);
  const double root_half = std::sqrt(0.5);
  for (int j = 0; j <= 1; ++j) {
    p.set(0, j, {1, 0, j});
    p.set(1, j, {1, 1, j}, root_half);
    p.set(2, j, {0, 1, j});
  }
  std::mt19937_64 rng(7);
  for (double eps : {0.01, 0.001, 0.0001}) {
    const ts::StepSizes s = ts::deviation_steps(ts::net_bounds(p), eps);
    const Worst w = worst_deviation(p, s, rng, 2000);
    INFO(describe(p, s, w, eps));
    CHECK(w.deviation <= eps);
  }
}

TEST_CASE("negative control: too few steps break the tolerance on a patch where the bound is tight",
          "[tessellate][steps][negative]") {
  const ts::BezierPatch p = parabolic_cylinder();
  std::mt19937_64 rng(3);
  const double eps = 0.001;
  const ts::StepSizes bound = ts::deviation_steps(ts::net_bounds(p), eps);
  const Worst ok = worst_deviation(p, bound, rng, 4000);
  INFO(describe(p, bound, ok, eps));
  CHECK(ok.deviation <= eps);
  const ts::StepSizes halved{std::max(1, bound.n_u / 2), bound.n_v};
  const Worst bad = worst_deviation(p, halved, rng, 4000);
  INFO(describe(p, halved, bad, eps));
  CHECK(bad.deviation > eps);
}

TEST_CASE("size bound: no grid edge along u or v is longer than asked", "[tessellate][steps]") {
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 40; ++trial) {
    const ts::BezierPatch p = random_patch(rng, 1 + trial % 4, 1 + trial % 3, trial % 2 == 1);
    const double edge = 0.05;
    const ts::StepSizes s = ts::size_steps(ts::net_bounds(p), edge);
    ts::TriangleBuffers tri;
    std::vector<ts::BernsteinTable> scratch;
    ts::tessellate_untrimmed(p, s, tri, scratch);
    const auto at = [&](int i, int j) { return glm::dvec3(tri.positions[i * (s.n_v + 1) + j]); };
    double longest = 0;
    for (int i = 0; i <= s.n_u; ++i) {
      for (int j = 0; j <= s.n_v; ++j) {
        if (i < s.n_u) longest = std::max(longest, glm::length(at(i + 1, j) - at(i, j)));
        if (j < s.n_v) longest = std::max(longest, glm::length(at(i, j + 1) - at(i, j)));
      }
    }
    INFO("trial " << trial << " steps " << s.n_u << "x" << s.n_v << " longest grid edge " << longest);
    CHECK(longest <= edge * (1 + 1e-6));
  }
}

TEST_CASE("grid buffers: vertex and triangle counts, capacity kept across frames", "[tessellate][grid]") {
  const ts::BezierPatch p = parabolic_cylinder();
  ts::TriangleBuffers tri;
  std::vector<ts::BernsteinTable> scratch;
  ts::tessellate_untrimmed(p, {8, 5}, tri, scratch);
  CHECK(tri.positions.size() == 9u * 6u);
  CHECK(tri.normals.size() == tri.positions.size());
  CHECK(tri.triangle_count() == 2u * 8u * 5u);
  const auto* before = tri.positions.data();
  ts::tessellate_untrimmed(p, {8, 5}, tri, scratch);  // same size again: no reallocation
  CHECK(tri.positions.data() == before);
}

TEST_CASE("pixel tolerance to object space", "[tessellate][steps]") {
  // 1 px at depth 10 with a 90° field of view on a 1000 px viewport: f = 500 px, ε = 10/500 = 0.02.
  CHECK(ts::object_tolerance(1.0, 10.0, 1000.0, 3.14159265358979 / 2) == Approx(0.02));
}
