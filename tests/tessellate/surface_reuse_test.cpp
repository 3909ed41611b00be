// Frame-to-frame reuse (tessellate/surface_reuse.hpp, FrameWorkload::set_reuse):
//   - along the main job's camera path, every surface's buffer with reuse is byte for byte the buffer of a
//     second scene tessellated afresh every frame, and the results (triangles, audit flags) are the same;
//     reuse happens (fewer surfaces remade than there are) and frame 0 makes every surface;
//   - each part of the key is needed: a kept key told that only the steps, or only the trim polylines, did not
//     change keeps a buffer that differs from the fresh one (the comparison above would catch it);
//   - prime() makes a run of frames start from the same state whatever ran before.
#include "tessellate/surface_reuse.hpp"

#include <catch2/catch.hpp>

#include <cstdint>

#include "tessellate/frame_workload.hpp"

namespace ts = frontsteal::tess;
using frontsteal::ItemId;

namespace {

ts::PathSceneOptions options(int frames) {
  ts::PathSceneOptions o{.scene = "plant:400",
                         .data_dir = FRONTSTEAL_DATA_DIR,
                         .path = ts::CameraPathKind::orbit_then_zoom,
                         .frames = frames,
                         .width = 640,
                         .height = 360,
                         .settings = {}};
  o.settings.pixel_tolerance = 1;
  return o;
}

bool same_bytes(const ts::TriangleBuffers& a, const ts::TriangleBuffers& b) {
  return a.positions == b.positions && a.normals == b.normals && a.uvs == b.uvs && a.indices == b.indices;
}

}  // namespace

TEST_CASE("reuse: the same bytes and results as tessellating every surface every frame, with less work",
          "[tessellate][reuse]") {
  constexpr int kFrames = 24;
  ts::PathScene reused_scene = ts::make_path_scene(options(kFrames));
  ts::PathScene fresh_scene = ts::make_path_scene(options(kFrames));
  ts::FrameWorkload reused(reused_scene, 2), fresh(fresh_scene, 1);
  reused.set_reuse(true);
  REQUIRE(reused.reuse());
  std::uint64_t remade_total = 0, kept_total = 0;
  for (int f = 0; f < kFrames; ++f) {
    for (ItemId id = 0; id < reused.surfaces(); ++id) {
      const ts::SurfaceResult a = reused.run(f, id, static_cast<frontsteal::WorkerId>(id % 2));
      const ts::SurfaceResult b = fresh.run(f, id, 0);
      INFO("frame " << f << ", surface " << id);
      REQUIRE(a.triangles == b.triangles);
      REQUIRE(a.inconsistencies() == b.inconsistencies());
      REQUIRE(a.capped == b.capped);
      REQUIRE(a.culled == b.culled);
      REQUIRE(same_bytes(reused_scene.buffers[id], fresh_scene.buffers[id]));
    }
    REQUIRE(reused.frame_triangles() == fresh.frame_triangles());
    REQUIRE(fresh.count_remade() == fresh.surfaces());
    if (f == 0) REQUIRE(reused.count_remade() == reused.surfaces());
    if (f > 0) remade_total += reused.count_remade(), kept_total += reused.surfaces() - reused.count_remade();
  }
  INFO("surfaces remade in frames 1.." << kFrames - 1 << ": " << remade_total << ", kept: " << kept_total);
  CHECK(kept_total > 0);
  CHECK(remade_total > 0);
}

TEST_CASE("negative control: a key that misses the steps or the trim polylines keeps stale triangles",
          "[tessellate][reuse]") {
  constexpr int kFrames = 24;
  ts::PathScene scene = ts::make_path_scene(options(kFrames));
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out, fresh;
  int stale_by_steps = 0, stale_by_trim = 0;
  for (ItemId id = 0; id < scene.surfaces(); ++id) {
    const ts::PreparedSurface& s = scene.prepared[id];
    for (int f = 1; f < kFrames; ++f) {
      const auto plan_of = [&](int frame) {
        return ts::plan_surface(s, scene.cameras[frame], scene.frusta[frame], scene.settings);
      };
      const ts::SurfacePlan before = plan_of(f - 1), now = plan_of(f);
      if (before.culled != ts::Culled::no || now.culled != ts::Culled::no) continue;
      ts::TessellationKey key_before, key_now;
      ts::make_tessellation_key(s, before, scene.settings, key_before);
      ts::make_tessellation_key(s, now, scene.settings, key_now);
      const bool steps_changed = key_before.steps != key_now.steps;
      const bool trim_changed = key_before.trim_steps != key_now.trim_steps;
      if (steps_changed == trim_changed) continue;  // exactly one part of the key changed
      if ((steps_changed ? stale_by_steps : stale_by_trim) >= 3) continue;
      ts::KeptTessellation kept;
      (void)ts::tessellate_or_reuse(s, scene.cameras[f - 1], scene.frusta[f - 1], scene.settings, scratch, out, kept);
      kept.key = key_now;  // the planted defect: a key blind to the part that changed
      const ts::ReuseOutcome o =
          ts::tessellate_or_reuse(s, scene.cameras[f], scene.frusta[f], scene.settings, scratch, out, kept);
      REQUIRE_FALSE(o.remade);
      ts::tessellate_planned(s, now, scene.settings, scratch, fresh);
      if (!same_bytes(out, fresh)) ++(steps_changed ? stale_by_steps : stale_by_trim);
    }
  }
  CHECK(stale_by_steps >= 3);
  CHECK(stale_by_trim >= 3);
}

TEST_CASE("reuse: prime() starts a run of frames from the same state whatever ran before", "[tessellate][reuse]") {
  constexpr int kFrames = 8;
  ts::PathScene scene = ts::make_path_scene(options(kFrames));
  ts::FrameWorkload frames(scene, 1);
  frames.set_reuse(true);
  const auto run_frame = [&](int f) {
    for (ItemId id = 0; id < frames.surfaces(); ++id) frames.run(f, id, 0);
    return frames.count_remade();
  };
  frames.prime(5);
  const std::uint64_t after_prime = run_frame(5);
  for (int f = 0; f < kFrames; ++f) run_frame(f);  // leaves frame 7's state
  frames.prime(5);
  CHECK(run_frame(5) == after_prime);
  frames.prime(0);
  CHECK(run_frame(0) == frames.surfaces());
  // Without reuse prime() is nothing and every frame remakes everything.
  ts::FrameWorkload plain(scene, 1);
  plain.prime(3);
  for (ItemId id = 0; id < plain.surfaces(); ++id) plain.run(3, id, 0);
  CHECK(plain.count_remade() == plain.surfaces());
}
