// The frame workload (tessellate/frame_workload.hpp) every measuring program runs its items through:
//   - run(f, id, w) is the scene's own tessellate() of that surface (checked against a direct call on a second
//     scene with its own scratch), whichever worker's scratch it uses;
//   - the frame's totals are the sums over surfaces of the latest results, counted here independently;
//   - a planted triangulation defect is counted and named (the audit flags reach the totals), and a step cap
//     low enough to bind is counted as capped;
//   - prepare_workers only grows.
#include "tessellate/frame_workload.hpp"

#include <catch2/catch.hpp>

#include <cstdint>

namespace ts = frontsteal::tess;
using frontsteal::ItemId;

namespace {

ts::PathSceneOptions options(ts::PlantedDefect defect = ts::PlantedDefect::none, int max_steps = 256,
                             const char* scene = "plant:150") {
  ts::PathSceneOptions o{.scene = scene,
                         .data_dir = FRONTSTEAL_DATA_DIR,
                         .path = ts::CameraPathKind::orbit_then_zoom,
                         .frames = 4,
                         .width = 640,
                         .height = 360,
                         .settings = {}};
  o.settings.pixel_tolerance = 1;
  o.settings.planted_defect = defect;
  o.settings.max_steps = max_steps;
  return o;
}

}  // namespace

TEST_CASE("frame workload: items are the scene's tessellations, totals their sums, on any worker") {
  ts::PathScene scene = ts::make_path_scene(options());
  ts::PathScene reference = ts::make_path_scene(options());
  ts::FrameWorkload frames(scene, 3);
  REQUIRE(frames.workers() == 3);
  REQUIRE(frames.surfaces() == 150);
  REQUIRE(frames.frames() == 4);
  ts::TessellationScratch scratch;
  for (int f = 0; f < 4; ++f) {
    std::uint64_t expected = 0;
    for (ItemId id = 0; id < frames.surfaces(); ++id) {
      const ts::SurfaceResult r = frames.run(f, id, static_cast<frontsteal::WorkerId>((id + f) % 3));
      const ts::SurfaceResult direct = reference.tessellate(f, id, scratch);
      REQUIRE(r.triangles == direct.triangles);
      REQUIRE(scene.buffers[id].positions == reference.buffers[id].positions);
      expected += direct.triangles;
    }
    REQUIRE(frames.frame_triangles() == expected);
    REQUIRE(frames.count_inconsistent() == 0);
    REQUIRE(frames.first_inconsistent().empty());
  }
  frames.prepare_workers(2);
  REQUIRE(frames.workers() == 3);
  frames.prepare_workers(5);
  REQUIRE(frames.workers() == 5);
}

TEST_CASE("frame workload: a planted defect reaches the audit totals, a binding step cap the capped count") {
  ts::PathScene broken = ts::make_path_scene(options(ts::PlantedDefect::drop_ear));
  ts::FrameWorkload frames(broken, 1);
  std::uint64_t flagged = 0;
  std::string first;
  for (ItemId id = 0; id < frames.surfaces(); ++id) {
    if (frames.run(3, id, 0).inconsistencies() > 0) {
      ++flagged;
      if (first.empty()) first = broken.model.surfaces[id].name;
    }
  }
  REQUIRE(flagged > 0);
  REQUIRE(frames.count_inconsistent() == flagged);
  REQUIRE(frames.first_inconsistent() == first);

  // The teapot's patches are curved everywhere: at 1 px two steps per direction are not enough.
  ts::PathScene capped = ts::make_path_scene(options(ts::PlantedDefect::none, 2, "teapot"));
  ts::FrameWorkload small(capped, 1);
  std::uint64_t held = 0;
  for (ItemId id = 0; id < small.surfaces(); ++id) held += small.run(0, id, 0).capped ? 1 : 0;
  REQUIRE(held > 0);
  REQUIRE(small.count_capped() == held);
}
