// The phase profile (tessellate/phase_profile.hpp): every tessellated surface's time lands in the phases its
// path goes through (untrimmed grids, or the trimmed path's polylines, trace, cells, triangulation and audit),
// the phases add up to no more than the harness's own clock measured around the same calls, and attaching a
// profile changes no triangle.
#include <chrono>

#include <catch2/catch.hpp>

#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;

TEST_CASE("phase profile: time lands in the phases each path runs, within the harness's clock, same triangles",
          "[tessellate][profile]") {
  const ts::Model model = ts::generate_plant({600, 3});
  std::vector<ts::PreparedSurface> prepared;
  for (const ts::Surface& s : model.surfaces) prepared.push_back(ts::prepare_surface(s));
  const ts::Camera cam = ts::camera_on_path(ts::model_box(model), 0, 16);
  const ts::Frustum frustum = ts::Frustum::of(cam);

  ts::TessellationScratch plain, profiled;
  ts::PhaseProfile profile;
  profiled.profile = &profile;
  ts::TriangleBuffers a, b;
  std::size_t visible_untrimmed = 0, visible_trimmed = 0, culled = 0;
  double wall = 0;
  for (const ts::PreparedSurface& s : prepared) {
    const ts::SurfaceResult ra = ts::tessellate_surface(s, cam, frustum, {}, plain, a);
    const auto start = std::chrono::steady_clock::now();
    const ts::SurfaceResult rb = ts::tessellate_surface(s, cam, frustum, {}, profiled, b);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    REQUIRE(ra.triangles == rb.triangles);
    REQUIRE(a.positions == b.positions);
    REQUIRE(a.indices == b.indices);
    if (rb.culled != ts::Culled::no) {
      ++culled;
    } else {
      (s.trimmed() ? visible_trimmed : visible_untrimmed) += 1;
    }
  }
  REQUIRE(visible_trimmed > 0);
  REQUIRE(visible_untrimmed > 0);
  const auto marks = [&](ts::Phase p) { return profile.marks[static_cast<std::size_t>(p)]; };
  CHECK(marks(ts::Phase::cull) == culled);
  CHECK(marks(ts::Phase::plan) == visible_trimmed + visible_untrimmed);
  CHECK(marks(ts::Phase::untrimmed_grid) == visible_untrimmed);
  CHECK(marks(ts::Phase::trim_polylines) == visible_trimmed);
  CHECK(marks(ts::Phase::trace) >= visible_trimmed);
  CHECK(marks(ts::Phase::triangulate) == marks(ts::Phase::audit));  // one of each per piece
  CHECK(marks(ts::Phase::triangulate) > 0);
  for (std::size_t p = 0; p < ts::kPhaseCount; ++p) CHECK(profile.seconds[p] >= 0);
  CHECK(profile.total() > 0);
  CHECK(profile.total() <= wall);

  // Without a profile, nothing is recorded anywhere: a lap on no profile is a no-op.
  ts::PhaseLap lap(nullptr);
  lap.to(ts::Phase::audit);
  CHECK(std::string(ts::to_string(ts::Phase::trimmed_cells)) == "trimmed cells");
}
