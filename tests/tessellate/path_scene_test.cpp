// The scene along a camera path (tessellate/path_scene.hpp), which the main job, frontsteal-paper and
// frontsteal-mpi all tessellate:
//   - one camera and frustum per frame, on the path asked for (checked against camera_on, called here
//     directly), one buffer per surface, and the settings as given;
//   - tessellate() is tessellate_surface on that frame's view (checked against a direct call with its own
//     scratch and buffers);
//   - the hints: one centre and one estimate (at least 1) per surface;
//   - a scene without surfaces, or a bad scene, is an error, not an empty scene.
#include "tessellate/path_scene.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>

namespace ts = frontsteal::tess;

TEST_CASE("path scene: the views of the path asked for, and tessellate() on them") {
  for (const ts::CameraPathKind kind : {ts::CameraPathKind::orbit_then_zoom, ts::CameraPathKind::dense_zoom}) {
    ts::PathSceneOptions o{.scene = "plant:120",
                           .data_dir = FRONTSTEAL_DATA_DIR,
                           .path = kind,
                           .frames = 5,
                           .width = 640,
                           .height = 360,
                           .settings = {}};
    o.settings.pixel_tolerance = 2;
    ts::PathScene s = ts::make_path_scene(o);
    REQUIRE(s.frames() == 5);
    REQUIRE(s.surfaces() == 120);
    REQUIRE(s.buffers.size() == 120);
    REQUIRE(s.frusta.size() == 5);
    REQUIRE(s.settings.pixel_tolerance == 2);
    const ts::Box box = ts::model_box(s.model);
    const ts::DenseRegion dense = ts::densest_region(s.model);
    for (int f = 0; f < 5; ++f) {
      const ts::Camera expected = ts::camera_on(kind, box, f, 5, 640, 360, &dense);
      REQUIRE(s.cameras[f].eye == expected.eye);
      REQUIRE(s.cameras[f].target == expected.target);
    }
    ts::TessellationScratch mine, theirs;
    ts::TriangleBuffers direct;
    for (int f : {0, 4}) {
      for (frontsteal::ItemId id : {0u, 57u, 119u}) {
        const ts::SurfaceResult a = s.tessellate(f, id, mine);
        const ts::Camera cam = ts::camera_on(kind, box, f, 5, 640, 360, &dense);
        const ts::SurfaceResult b = ts::tessellate_surface(ts::prepare_surface(s.model.surfaces[id]), cam,
                                                           ts::Frustum::of(cam), o.settings, theirs, direct);
        REQUIRE(a.triangles == b.triangles);
        REQUIRE(s.buffers[id].positions == direct.positions);
      }
    }
    REQUIRE(s.centres().size() == 120);
    for (double c : s.estimated_costs(4)) REQUIRE(c >= 1.0);
  }
}

TEST_CASE("path scene: a bad scene is an error") {
  REQUIRE_THROWS(ts::make_path_scene({.scene = "plant:0", .data_dir = FRONTSTEAL_DATA_DIR}));
  REQUIRE_THROWS(ts::make_path_scene({.scene = "no-such-scene", .data_dir = FRONTSTEAL_DATA_DIR}));
}
