// Rational Bézier patch evaluation (tessellate/bezier_patch.hpp): fixed-seed property tests that print the
// counterexample.
#include "tessellate/bezier_patch.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "tests/tessellate/random_patch.hpp"

namespace ts = frontsteal::tess;
using frontsteal::tess::testing::random_patch;

namespace {

// A quarter of the unit cylinder around the z axis: rational quadratic in u (weights 1, √2/2, 1), linear in v.
ts::BezierPatch quarter_cylinder() {
  ts::BezierPatch p(2, 1);
  const double w = std::sqrt(0.5);
  for (int j = 0; j <= 1; ++j) {
    const double z = j;
    p.set(0, j, {1, 0, z});
    p.set(1, j, {1, 1, z}, w);
    p.set(2, j, {0, 1, z});
  }
  return p;
}

}  // namespace

TEST_CASE("Bernstein bases sum to one and their derivatives to zero", "[tessellate][patch]") {
  for (int d = 1; d <= ts::kMaxDegree; ++d) {
    for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const ts::BernsteinTable b = ts::bernstein(d, t);
      double sum = 0, dsum = 0;
      for (int i = 0; i <= d; ++i) {
        sum += b.value[i];
        dsum += b.derivative[i];
      }
      INFO("degree " << d << " t " << t);
      CHECK(sum == Approx(1.0));
      CHECK(dsum == Approx(0.0).margin(1e-12));
    }
  }
}

TEST_CASE("a patch interpolates its corner control points", "[tessellate][patch]") {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const int du = 1 + trial % ts::kMaxDegree;
    const int dv = 1 + (trial * 3) % ts::kMaxDegree;
    const ts::BezierPatch p = random_patch(rng, du, dv, trial % 2 == 1);
    for (auto [u, v, i, j] : {std::tuple{0.0, 0.0, 0, 0}, {1.0, 0.0, du, 0}, {0.0, 1.0, 0, dv}, {1.0, 1.0, du, dv}}) {
      const glm::dvec3 s = ts::evaluate(p, u, v).position;
      INFO("trial " << trial << " degrees " << du << "x" << dv << " corner (" << u << "," << v << ")");
      CHECK(glm::length(s - p.point(i, j)) < 1e-12);
    }
  }
}

TEST_CASE("partial derivatives match finite differences", "[tessellate][patch]") {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> param(0.05, 0.95);
  for (int trial = 0; trial < 100; ++trial) {
    const ts::BezierPatch p = random_patch(rng, 1 + trial % 7, 1 + (trial / 7) % 7, trial % 3 == 0);
    const double u = param(rng), v = param(rng), h = 1e-6;
    const ts::SurfacePoint sp = ts::evaluate(p, u, v);
    const glm::dvec3 fu = (ts::evaluate(p, u + h, v).position - ts::evaluate(p, u - h, v).position) / (2 * h);
    const glm::dvec3 fv = (ts::evaluate(p, u, v + h).position - ts::evaluate(p, u, v - h).position) / (2 * h);
    INFO("trial " << trial << " at (" << u << "," << v << ")");
    CHECK(glm::length(sp.du - fu) < 1e-5 * (1 + glm::length(fu)));
    CHECK(glm::length(sp.dv - fv) < 1e-5 * (1 + glm::length(fv)));
  }
}

TEST_CASE("the rational quarter cylinder lies exactly on the unit cylinder", "[tessellate][patch]") {
  const ts::BezierPatch p = quarter_cylinder();
  for (double u = 0; u <= 1.0; u += 0.0625) {
    for (double v : {0.0, 0.4, 1.0}) {
      const ts::SurfacePoint sp = ts::evaluate(p, u, v);
      INFO("(u,v) = (" << u << "," << v << ")");
      CHECK(std::hypot(sp.position.x, sp.position.y) == Approx(1.0).epsilon(1e-12));
      CHECK(sp.position.z == Approx(v));
      // The normal is radial: S_u × S_v points away from (or towards) the axis.
      CHECK(std::abs(glm::dot(sp.normal, glm::normalize(glm::dvec3(sp.position.x, sp.position.y, 0)))) ==
            Approx(1.0).epsilon(1e-9));
    }
  }
}

TEST_CASE("a collapsed edge still gets a normal", "[tessellate][patch]") {
  // A bicubic patch whose v = 0 edge collapses to a point (like the teapot lid's pole).
  ts::BezierPatch p(3, 3);
  for (int i = 0; i <= 3; ++i) {
    for (int j = 0; j <= 3; ++j) {
      const double r = j / 3.0, a = i * 0.5;
      p.set(i, j, {r * std::cos(a), r * std::sin(a), 1 - r * r});
    }
  }
  const ts::SurfacePoint pole = ts::evaluate(p, 0.5, 0.0);
  CHECK(glm::length(pole.normal) == Approx(1.0));
  CHECK(std::abs(pole.normal.z) > 0.9);  // the pole's normal is the axis
}

TEST_CASE("bad degrees are rejected with a clear message", "[tessellate][patch]") {
  CHECK_THROWS_WITH(ts::BezierPatch(0, 3), Catch::Contains("degree must be 1..25"));
  CHECK_THROWS_WITH(ts::BezierPatch(3, 26), Catch::Contains("got 3x26"));
}
