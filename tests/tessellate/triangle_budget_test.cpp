// The per-frame triangle budget (tessellate/triangle_budget.hpp). Fixed-seed scenes of plates at random
// distances along the line of sight, with random step counts:
//   - the untrimmed prediction is exactly what tessellate_untrimmed emits; the trimmed estimate is close;
//   - an achievable budget is met, by the prediction and by the triangles actually emitted;
//   - the farthest surfaces are coarsened first (negative control: nearest-first must break the check);
//   - under budget nothing changes; an unachievable budget leaves every visible surface at 1 × 1 and says so;
//   - culled surfaces are never touched; coarsened trimmed surfaces still pass the tiling audit.
#include "tessellate/triangle_budget.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/tessellate/trim_shapes.hpp"

namespace ts = frontsteal::tess;
using namespace frontsteal::tess::testing;

namespace {

// `count` unit plates facing the eye at the origin (line of sight +x), at random distances 2..200, with random
// steps 1..64 in each direction; every fourth trimmed by a circular hole. Index order is unrelated to distance.
struct Scene {
  ts::Model model;
  std::vector<ts::PreparedSurface> prepared;
  std::vector<ts::SurfacePlan> plans;
  ts::Camera camera;

  Scene(std::uint64_t seed, int count) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> dist(2.0, 200.0), side(-3.0, 3.0);
    std::uniform_int_distribution<int> steps(1, 64);
    camera.eye = {0, 0, 0};
    camera.target = {1, 0, 0};
    camera.far_plane = 1000;
    model.surfaces.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) {
      ts::Surface& s = model.surfaces[static_cast<std::size_t>(k)];
      s.name = "plate" + std::to_string(k);
      const glm::dvec3 o(dist(rng), side(rng), side(rng));
      s.patch = ts::BezierPatch(1, 1);
      s.patch.set(0, 0, o);
      s.patch.set(1, 0, o + glm::dvec3(0, 1, 0));
      s.patch.set(0, 1, o + glm::dvec3(0, 0, 1));
      s.patch.set(1, 1, o + glm::dvec3(0, 1, 1));
      if (k % 4 == 3) {
        s.loops.push_back(polyline_loop({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}}));
        s.loops.push_back(circle_loop({0.5, 0.5}, 0.3, false));
      }
    }
    for (const ts::Surface& s : model.surfaces) prepared.push_back(ts::prepare_surface(s));
    for (std::size_t k = 0; k < prepared.size(); ++k) {
      ts::SurfacePlan p;
      p.epsilon = 1e-3;
      p.edge_length = 0.05;
      p.steps = {steps(rng), steps(rng)};
      plans.push_back(p);
    }
  }
  std::uint64_t predicted(const ts::TessellationSettings& settings) const {
    std::uint64_t n = 0;
    for (std::size_t k = 0; k < plans.size(); ++k) n += ts::predict_triangles(prepared[k], plans[k], settings);
    return n;
  }
};

// How many halvings (n ↦ max(1, n/2) in both directions) turn `before` into `after`.
int halvings(ts::StepSizes before, ts::StepSizes after) {
  int h = 0;
  while (!(before == after)) {
    if (before == ts::StepSizes{1, 1}) return -1;  // not reachable by halving
    before = {std::max(1, before.n_u / 2), std::max(1, before.n_v / 2)};
    ++h;
  }
  return h;
}

// The farthest-first property: if a surface was halved h times, every visible surface farther from the eye was
// halved at least h times, unless it reached 1 × 1 first. Returns a counterexample, or "" when it holds.
std::string farthest_first_violation(const Scene& sc, const std::vector<ts::SurfacePlan>& before) {
  const auto dist = [&](std::size_t k) { return ts::detail::distance_to_box(sc.prepared[k].box, sc.camera.eye); };
  for (std::size_t near = 0; near < sc.plans.size(); ++near) {
    const int h_near = halvings(before[near].steps, sc.plans[near].steps);
    for (std::size_t far = 0; far < sc.plans.size(); ++far) {
      if (dist(far) <= dist(near)) continue;
      const int h_far = halvings(before[far].steps, sc.plans[far].steps);
      if (h_far < h_near && !(sc.plans[far].steps == ts::StepSizes{1, 1})) {
        std::ostringstream s;
        s << "surface " << near << " at distance " << dist(near) << " halved " << h_near << " times, but surface "
          << far << " at distance " << dist(far) << " only " << h_far << " times (steps " << sc.plans[far].steps.n_u
          << "x" << sc.plans[far].steps.n_v << ")";
        return s.str();
      }
    }
  }
  return "";
}

// Tessellates every plan; returns the triangles emitted and adds up the audit's inconsistencies.
std::uint64_t emitted(const Scene& sc, const ts::TessellationSettings& settings, std::uint64_t& inconsistencies) {
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  std::uint64_t n = 0;
  for (std::size_t k = 0; k < sc.plans.size(); ++k) {
    const ts::SurfaceResult r = ts::tessellate_planned(sc.prepared[k], sc.plans[k], settings, scratch, out);
    n += r.triangles;
    inconsistencies += r.inconsistencies();
  }
  return n;
}

}  // namespace

TEST_CASE("triangle budget: the untrimmed prediction is exact, the trimmed estimate within 25 percent", "[fast]") {
  const ts::TessellationSettings settings;
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Scene sc(seed, 40);
    for (std::size_t k = 0; k < sc.plans.size(); ++k) {
      const ts::SurfaceResult r = ts::tessellate_planned(sc.prepared[k], sc.plans[k], settings, scratch, out);
      const double predicted = static_cast<double>(ts::predict_triangles(sc.prepared[k], sc.plans[k], settings));
      INFO("seed " << seed << ", surface " << k << ", steps " << sc.plans[k].steps.n_u << "x" << sc.plans[k].steps.n_v
                   << ": predicted " << predicted << ", emitted " << r.triangles);
      if (sc.prepared[k].trimmed()) {
        // Small grids are dominated by the hole's 4 cubic arcs; the estimate is meant for the sizes a budget acts on.
        if (r.triangles >= 64) CHECK(std::abs(predicted - r.triangles) <= 0.25 * r.triangles);
      } else {
        CHECK(predicted == r.triangles);
      }
    }
  }
}

TEST_CASE("triangle budget: an achievable budget is met by the prediction and by the emitted triangles", "[fast]") {
  const ts::TessellationSettings settings;
  for (const std::uint64_t seed : {11u, 12u, 13u}) {
    for (const double fraction : {0.9, 0.5, 0.1, 0.02}) {
      Scene sc(seed, 60);
      const std::uint64_t total = sc.predicted(settings);
      const std::uint64_t budget = static_cast<std::uint64_t>(fraction * static_cast<double>(total));
      const ts::BudgetOutcome b = ts::apply_triangle_budget(sc.prepared, sc.plans, sc.camera, settings, budget);
      std::uint64_t inconsistencies = 0;
      const std::uint64_t n = emitted(sc, settings, inconsistencies);
      INFO("seed " << seed << ", budget " << budget << " of " << total << ": predicted " << b.predicted_after
                   << ", emitted " << n << ", coarsened " << b.coarsened);
      CHECK(b.met);
      CHECK(b.predicted_before == total);
      CHECK(b.predicted_after <= budget);
      CHECK(b.predicted_after == sc.predicted(settings));
      CHECK(b.coarsened > 0);
      // The emitted count follows the prediction: exact for the untrimmed three quarters, an estimate for the rest.
      CHECK(static_cast<double>(n) <= 1.05 * static_cast<double>(budget));
      CHECK(inconsistencies == 0);  // coarser steps are still exact tilings
    }
  }
}

TEST_CASE("triangle budget: the farthest surfaces are coarsened first, nearest-first fails the check", "[fast]") {
  const ts::TessellationSettings settings;
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    for (const double fraction : {0.7, 0.3, 0.05}) {
      Scene sc(seed, 60);
      const std::vector<ts::SurfacePlan> before = sc.plans;
      const auto budget = static_cast<std::uint64_t>(fraction * static_cast<double>(sc.predicted(settings)));
      const ts::BudgetOutcome b = ts::apply_triangle_budget(sc.prepared, sc.plans, sc.camera, settings, budget);
      INFO("seed " << seed << ", budget " << budget);
      REQUIRE(b.met);
      CHECK(farthest_first_violation(sc, before) == "");
    }
  }
  // Negative control: the same scenes coarsened nearest first must show a violation.
  for (const std::uint64_t seed : {21u, 22u, 23u}) {
    Scene sc(seed, 60);
    const std::vector<ts::SurfacePlan> before = sc.plans;
    const auto budget = static_cast<std::uint64_t>(0.7 * static_cast<double>(sc.predicted(settings)));
    const ts::BudgetOutcome b = ts::apply_triangle_budget(sc.prepared, sc.plans, sc.camera, settings, budget,
                                                          ts::CoarseningOrder::nearest_first);
    INFO("seed " << seed << ", negative control (nearest first)");
    REQUIRE(b.met);
    CHECK(farthest_first_violation(sc, before) != "");
  }
}

TEST_CASE("triangle budget: under budget nothing changes", "[fast]") {
  const ts::TessellationSettings settings;
  Scene sc(31, 50);
  const std::vector<ts::SurfacePlan> before = sc.plans;
  const std::uint64_t total = sc.predicted(settings);
  for (const std::uint64_t budget : {total, total + 1, 10 * total}) {
    const ts::BudgetOutcome b = ts::apply_triangle_budget(sc.prepared, sc.plans, sc.camera, settings, budget);
    CHECK(b.met);
    CHECK(b.coarsened == 0);
    CHECK(b.predicted_after == total);
    for (std::size_t k = 0; k < before.size(); ++k) {
      INFO("budget " << budget << ", surface " << k);
      CHECK(sc.plans[k].steps == before[k].steps);
      CHECK(sc.plans[k].epsilon == before[k].epsilon);
      CHECK(sc.plans[k].edge_length == before[k].edge_length);
    }
  }
}

TEST_CASE("triangle budget: an unachievable budget leaves 1 x 1 grids and is reported, culled surfaces untouched",
          "[fast]") {
  const ts::TessellationSettings settings;
  Scene sc(41, 30);
  for (std::size_t k = 0; k < sc.plans.size(); k += 5) sc.plans[k].culled = ts::Culled::frustum;
  const std::vector<ts::SurfacePlan> before = sc.plans;
  const ts::BudgetOutcome b = ts::apply_triangle_budget(sc.prepared, sc.plans, sc.camera, settings, 1);
  CHECK_FALSE(b.met);
  CHECK(b.predicted_after > 1);
  for (std::size_t k = 0; k < sc.plans.size(); ++k) {
    INFO("surface " << k);
    if (before[k].culled != ts::Culled::no) {
      CHECK(sc.plans[k].steps == before[k].steps);
    } else {
      CHECK(sc.plans[k].steps == ts::StepSizes{1, 1});
    }
  }
  // Deterministic: the same input gives the same plans.
  Scene again(41, 30);
  for (std::size_t k = 0; k < again.plans.size(); k += 5) again.plans[k].culled = ts::Culled::frustum;
  const ts::BudgetOutcome b2 = ts::apply_triangle_budget(again.prepared, again.plans, again.camera, settings, 1);
  CHECK(b2.predicted_after == b.predicted_after);
  for (std::size_t k = 0; k < sc.plans.size(); ++k) CHECK(again.plans[k].steps == sc.plans[k].steps);
}
