// The single-precision SIMD grid (tessellate/grid_row_kernel.hpp, tessellate_untrimmed_float) against the
// double-precision grid of the same patch: positions within float_row_error_bound, normals within a small
// angle, for both builds of the kernel (AVX2+FMA where the CPU has it, and the baseline) and every degree.
// The bound is shown able to fail (a grid shifted by a fraction of a step exceeds it), and plan_surface falls
// back to double where the bound is not well inside the tolerance (far-off coordinates, extreme weights).
#include "tessellate/grid_row_kernel.hpp"

#include <catch2/catch.hpp>

#include <random>

#include "tessellate/grid_tessellator.hpp"
#include "tessellate/surface_tessellator.hpp"
#include "tests/tessellate/random_patch.hpp"

namespace ts = frontsteal::tess;
using frontsteal::tess::testing::random_patch;

namespace {

struct Difference {
  double position = 0, normal_angle = 0;
};

Difference compare(const ts::TriangleBuffers& a, const ts::TriangleBuffers& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.indices == b.indices);
  Difference d;
  for (std::size_t k = 0; k < a.positions.size(); ++k) {
    d.position = std::max(d.position, static_cast<double>(glm::length(a.positions[k] - b.positions[k])));
    const double c = std::clamp(static_cast<double>(glm::dot(a.normals[k], b.normals[k])), -1.0, 1.0);
    d.normal_angle = std::max(d.normal_angle, std::acos(c));
  }
  return d;
}

}  // namespace

TEST_CASE("float grid equals the double grid within its error bound, both kernel builds, every degree",
          "[float-grid]") {
  std::mt19937_64 rng(42);
  ts::TriangleBuffers exact, fast;
  std::vector<ts::BernsteinTable> basis;
  ts::FloatGridScratch scratch;
  for (ts::RowKernelBuild build : {ts::RowKernelBuild::best_for_cpu, ts::RowKernelBuild::baseline}) {
    ts::set_row_kernel_build(build);
    // Degrees 1..11 in both directions (the unrolled kernels go to 7, the run-time-degree one beyond), then
    // the largest degree.
    for (int trial = 0; trial < 204; ++trial) {
      const int du = trial < 200 ? 1 + trial % 11 : (trial % 2 == 0 ? ts::kMaxDegree : 2);
      const int dv = trial < 200 ? 1 + (trial / 11) % 11 : ts::kMaxDegree;
      const ts::BezierPatch patch = random_patch(rng, du, dv, trial % 2 == 1);
      const ts::StepSizes steps{1 + trial % 23, 1 + (trial * 7) % 41};
      ts::tessellate_untrimmed(patch, steps, exact, basis);
      ts::tessellate_untrimmed_float(patch, steps, fast, scratch);
      const Difference d = compare(exact, fast);
      // Both are stored as floats: add one rounding of the largest coordinate on top of the bound.
      const double bound = ts::float_row_error_bound(patch) + 1.2e-7 * 4.0;
      INFO("build " << static_cast<int>(build) << ", trial " << trial << ": degree " << du << "x" << dv << ", steps "
                    << steps.n_u << "x" << steps.n_v << ": position difference " << d.position << " (bound " << bound
                    << "), normal angle " << d.normal_angle);
      CHECK(d.position <= bound);
      CHECK(d.normal_angle < 1e-3);
    }
  }
  ts::set_row_kernel_build(ts::RowKernelBuild::best_for_cpu);
}

TEST_CASE("negative control: a grid a tenth of a step off exceeds the bound", "[float-grid]") {
  std::mt19937_64 rng(7);
  const ts::BezierPatch patch = random_patch(rng, 3, 3, true);
  ts::TriangleBuffers exact, shifted;
  std::vector<ts::BernsteinTable> basis;
  ts::tessellate_untrimmed(patch, {16, 16}, exact, basis);
  // The same grid evaluated a tenth of a step further along v, as a kernel with a wrong basis would.
  ts::tessellate_untrimmed(patch, {16, 16}, shifted, basis);
  for (std::size_t k = 0; k < shifted.positions.size(); ++k) {
    const glm::vec2 uv = shifted.uvs[k];
    shifted.positions[k] = glm::vec3(ts::evaluate(patch, uv.x, std::min(1.0, uv.y + 0.1 / 16)).position);
  }
  const Difference d = compare(exact, shifted);
  CHECK(d.position > 10 * ts::float_row_error_bound(patch));
}

TEST_CASE("plan_surface keeps double precision where the float bound is not well inside the tolerance",
          "[float-grid]") {
  std::mt19937_64 rng(3);
  ts::BezierPatch near = random_patch(rng, 3, 3, false);
  ts::BezierPatch far = near, heavy = near;
  for (glm::dvec4& h : far.control) h += glm::dvec4(1e7 * h.w, 0, 0, 0);  // the same shape, 10^7 units away
  heavy.control[5] *= 1e6;                                                // one weight 10^6 times the others
  ts::Camera cam;
  cam.target = {1e7 + 0.5, 0.5, 0.0};
  cam.eye = cam.target + glm::dvec3(0, -3, 2);
  ts::TessellationSettings settings;
  const auto plan = [&](const ts::BezierPatch& p, const ts::Camera& c) {
    const ts::Surface s{"s", p, {}, -1, false};
    return ts::plan_surface(ts::prepare_surface(s), c, ts::Frustum::of(c), settings);
  };
  ts::Camera home;
  home.target = {0.5, 0.5, 0.0};
  home.eye = {0.5, -2.5, 2.0};
  REQUIRE(plan(near, home).culled == ts::Culled::no);
  REQUIRE(plan(far, cam).culled == ts::Culled::no);  // in view: the fallback is the plan's choice, not culling
  REQUIRE(plan(heavy, home).culled == ts::Culled::no);
  CHECK(plan(near, home).single_precision);
  CHECK_FALSE(plan(far, cam).single_precision);
  CHECK_FALSE(plan(heavy, home).single_precision);
  settings.single_precision = false;
  CHECK_FALSE(plan(near, home).single_precision);
}
