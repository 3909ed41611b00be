// The limit arm (schedulers/main_job/limit_arm.hpp): P copies of the serial loop at once, each into buffers of
// its own. Every copy's frame has the serial loop's triangles and passes the tessellation's audit; the scene's
// own buffers (the serial loop's and every scheduler's) are never written by it; the throughput limit is the
// harmonic combination of the copies' times; a pool smaller than P is refused.
#include "schedulers/main_job/limit_arm.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>

namespace mj = frontsteal::main_job;
namespace ts = frontsteal::tess;
namespace ms = frontsteal::measure;
using frontsteal::ItemId;
using frontsteal::WorkerId;

namespace {

ts::PathSceneOptions options() {
  ts::PathSceneOptions o{.scene = "plant:150",
                         .data_dir = FRONTSTEAL_DATA_DIR,
                         .path = ts::CameraPathKind::orbit_then_zoom,
                         .frames = 4,
                         .width = 640,
                         .height = 360,
                         .settings = {}};
  o.settings.pixel_tolerance = 1;
  return o;
}

}  // namespace

TEST_CASE("every copy of the limit arm makes the serial loop's frame into buffers of its own", "[main-job][limit]") {
  ts::PathScene scene = ts::make_path_scene(options());
  ts::FrameWorkload serial(scene, 1);
  const WorkerId p = 3;
  mj::LimitCopies pool(scene, p, false);
  for (int f = 0; f < scene.frames(); ++f) {
    for (ItemId id = 0; id < scene.surfaces(); ++id) pool.grow(f, id);
  }
  for (auto& b : scene.buffers) b.clear();  // the copies must never write these
  ms::ItemSampler sampler(scene.surfaces(), p, 1);
  mj::LimitArm arm(
      pool, p, [](WorkerId) {}, sampler);
  for (int f = 0; f < scene.frames(); ++f) {
    const mj::LimitFrame& lf = arm.run_frame(f);
    std::uint64_t serial_triangles = 0;
    for (ItemId id = 0; id < scene.surfaces(); ++id) serial_triangles += serial.run(f, id, 0).triangles;
    REQUIRE(lf.triangles.size() == p);
    for (WorkerId w = 0; w < p; ++w) {
      CAPTURE(f, w);
      CHECK(lf.triangles[w] == serial_triangles);
      CHECK(lf.inconsistent[w] == 0);
      CHECK(lf.copy_ns[w] > 0);
    }
    CHECK(lf.throughput_ns() > 0);
    for (auto& b : scene.buffers) b.clear();  // the serial loop above wrote them
  }
  (void)sampler.take_frame();
  arm.run_frame(0);
  for (const auto& b : scene.buffers) CHECK(b.triangle_count() == 0);
}

TEST_CASE("the throughput limit combines the copies' rates", "[main-job][limit]") {
  mj::LimitFrame f;
  f.copy_ns = {100, 100};
  CHECK(f.throughput_ns() == Approx(50));  // two equal copies: half a copy's time per frame
  f.copy_ns = {100, 300};
  CHECK(f.throughput_ns() == Approx(75));  // 1 / (1/100 + 1/300)
  f.copy_ns = {};
  CHECK(f.throughput_ns() == 0);
}

TEST_CASE("a limit arm needs a copy per worker", "[main-job][limit]") {
  ts::PathScene scene = ts::make_path_scene(options());
  mj::LimitCopies pool(scene, 1, false);
  ms::ItemSampler sampler(scene.surfaces(), 2, 1);
  CHECK_THROWS_AS(mj::LimitArm(
                      pool, 2, [](WorkerId) {}, sampler),
                  std::invalid_argument);
}
