// path_spread_test.cpp — the main job's camera paths unbalance round robin as designed: the
// per-frame ratio max/min of the workers' summed cost, items dealt round robin, is larger on the walkthrough
// inside the plant and on the zoom that ends on the densest region than on the orbit. Deterministic: from the
// tessellator's per-surface cost ESTIMATES (estimate_cost), never from wall time. And the dense zoom does what
// it is for: at its end a few surfaces carry most of the frame's cost.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

#include "schedulers/main_job/round_robin_spread.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;
namespace sc = frontsteal::sched;

namespace {

struct Scene {
  ts::Model model;
  std::vector<ts::PreparedSurface> prepared;
  ts::Box box;
  ts::DenseRegion dense;
};

const Scene& plant() {
  static const Scene s = [] {
    Scene x;
    x.model = ts::load_scene("plant:1201", FRONTSTEAL_DATA_DIR);
    for (const ts::Surface& surf : x.model.surfaces) x.prepared.push_back(ts::prepare_surface(surf));
    x.box = ts::model_box(x.model);
    x.dense = ts::densest_region(x.model);
    return x;
  }();
  return s;
}

std::vector<std::vector<double>> estimated_costs(ts::CameraPathKind kind, int frames) {
  const Scene& s = plant();
  ts::TessellationSettings settings;
  std::vector<std::vector<double>> costs;
  for (int f = 0; f < frames; ++f) {
    const ts::Camera cam = ts::camera_on(kind, s.box, f, frames, 1280, 720, &s.dense);
    const ts::Frustum fr = ts::Frustum::of(cam);
    std::vector<double> c;
    for (const ts::PreparedSurface& p : s.prepared)
      c.push_back(ts::estimate_cost(p, ts::plan_surface(p, cam, fr, settings), settings));
    costs.push_back(std::move(c));
  }
  return costs;
}

}  // namespace

TEST_CASE("round_robin_spread deals item i to worker i mod P and reports max over min per frame", "[spread]") {
  // Frame 0: workers get 1+3 and 2+4 -> 6/4; frame 1: one costly item -> 100/2.
  const std::vector<std::vector<double>> costs{{1, 2, 3, 4}, {100, 1, 0, 1}};
  const sc::CostSpread s = sc::round_robin_spread(costs, 2);
  REQUIRE(s.per_frame.size() == 2);
  CHECK(s.per_frame[0] == Approx(1.5));
  CHECK(s.per_frame[1] == Approx(50.0));
  CHECK(s.worst == Approx(50.0));
  CHECK(s.worst_frame == 1);
  CHECK(s.median == Approx(25.75));
  CHECK(sc::round_robin_spread(costs, 1).worst == Approx(1.0));
  CHECK(std::isinf(sc::round_robin_spread({{1, 0}}, 2).worst));
}

TEST_CASE("densest_region is inside the model and holds several surfaces", "[spread]") {
  const Scene& s = plant();
  CHECK(s.dense.surfaces >= 4);
  const glm::dvec3 c = s.dense.box.centre();
  CHECK(c.x >= s.box.lo.x);
  CHECK(c.x <= s.box.hi.x);
  CHECK(c.y >= s.box.lo.y);
  CHECK(c.y <= s.box.hi.y);
  CHECK(ts::camera_path_named("dense-zoom") == ts::CameraPathKind::dense_zoom);
  CHECK(ts::camera_path_named("walkthrough") == ts::CameraPathKind::walkthrough);
  CHECK_FALSE(ts::camera_path_named("spiral").has_value());
  CHECK_THROWS_AS(ts::camera_on(ts::CameraPathKind::dense_zoom, s.box, 0, 4, 64, 64), std::invalid_argument);
}

TEST_CASE("walkthrough and dense-zoom unbalance round robin more than the orbit", "[spread]") {
  constexpr int kFrames = 12;
  const auto orbit = estimated_costs(ts::CameraPathKind::orbit, kFrames);
  const auto walk = estimated_costs(ts::CameraPathKind::walkthrough, kFrames);
  const auto dense = estimated_costs(ts::CameraPathKind::dense_zoom, kFrames);
  const auto otz = estimated_costs(ts::CameraPathKind::orbit_then_zoom, kFrames);
  // The share of the frame's estimated cost carried by its 16 costliest surfaces.
  auto top_share = [](std::vector<double> c) {
    double total = 0;
    for (double x : c) total += x;
    std::sort(c.begin(), c.end(), std::greater<>());
    double top = 0;
    for (std::size_t i = 0; i < 16 && i < c.size(); ++i) top += c[i];
    return top / total;
  };
  const double orbit_top = top_share(orbit.back()), dense_top = top_share(dense.back());
  std::cout << "16 costliest surfaces' share of the last frame (estimates): orbit " << orbit_top << ", dense-zoom "
            << dense_top << '\n';
  CHECK(dense_top > 0.4);
  CHECK(dense_top > 5 * orbit_top);
  for (std::size_t p : {2u, 4u}) {
    const double o = sc::round_robin_spread(orbit, p).worst;
    const double w = sc::round_robin_spread(walk, p).worst;
    const double d = sc::round_robin_spread(dense, p).worst;
    const double z = sc::round_robin_spread(otz, p).worst;

    std::cout << "P=" << p << " worst-frame round-robin max/min (estimates): orbit " << o << ", orbit-then-zoom " << z
              << ", walkthrough " << w << ", dense-zoom " << d << '\n';
    INFO("P=" << p << " orbit " << o << " walkthrough " << w << " dense-zoom " << d);
    CHECK(w > 1.5 * o);
    CHECK(d > 1.5 * o);
  }
}
