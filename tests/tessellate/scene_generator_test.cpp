// The procedural plant (tessellate/scene_generator.hpp): exact surface counts, deterministic by seed, valid
// in the native format, solids facing outwards, and a whole frame tessellates with no trimming inconsistency.
#include "tessellate/scene_generator.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <sstream>

#include "tessellate/model_format.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;

TEST_CASE("the paper's model sizes are generated exactly, deterministically", "[scene]") {
  for (int n : {1, 7, 30, 1201, 3392, 4101, 5302}) {
    const ts::Model m = ts::generate_plant({n, 3});
    CHECK(m.surfaces.size() == static_cast<std::size_t>(n));
  }
  const ts::Model a = ts::generate_plant({1201, 11}), b = ts::generate_plant({1201, 11}),
                  c = ts::generate_plant({1201, 12});
  std::ostringstream wa, wb, wc;
  ts::write_model(wa, a);
  ts::write_model(wb, b);
  ts::write_model(wc, c);
  CHECK(wa.str() == wb.str());
  CHECK(wa.str() != wc.str());
  CHECK_THROWS_AS(ts::generate_plant({0, 1}), std::invalid_argument);
  CHECK_THROWS_WITH(ts::load_scene("plant:12x", "."), Catch::Contains("plant:<surfaces>"));
}

TEST_CASE("a generated plant passes the strict parser and has trimmed surfaces, solids and components", "[scene]") {
  const ts::Model m = ts::generate_plant({1201, 5});
  std::ostringstream out;
  ts::write_model(out, m);
  std::istringstream in(out.str());
  const ts::Model back = ts::parse_model(in, "plant");
  REQUIRE(back.surfaces.size() == m.surfaces.size());
  int trimmed = 0, solids = 0, max_component = 0;
  // Outward normals: each closed solid's signed volume, Σ p₀·(p₁ × p₂)/6 over its triangles, is positive.
  std::map<int, double> volume;
  ts::TriangleBuffers tri;
  std::vector<ts::BernsteinTable> basis;
  for (const ts::Surface& s : m.surfaces) {
    trimmed += s.loops.size() > 1;
    solids += s.solid;
    max_component = std::max(max_component, s.component);
    if (!s.solid) continue;
    ts::tessellate_untrimmed(s.patch, {12, 12}, tri, basis);
    for (std::size_t t = 0; t < tri.indices.size(); t += 3) {
      const glm::dvec3 a = tri.positions[tri.indices[t]], b = tri.positions[tri.indices[t + 1]],
                       c = tri.positions[tri.indices[t + 2]];
      volume[s.component] += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
  }
  for (const auto& [component, v] : volume) {
    INFO("solid component " << component << ": signed volume " << v);
    CHECK(v > 10.0);  // a tank holds at least π·1.2²·4 − (heads' share) ≈ 16 m³
  }
  CHECK(trimmed > 100);
  CHECK(solids > 300);
  CHECK(max_component > 40);
}

TEST_CASE("a whole generated frame tessellates without trimming inconsistencies", "[scene]") {
  const ts::Model m = ts::generate_plant({3392, 2});
  ts::Camera cam;
  cam.eye = {-30, -40, 35};
  cam.target = {60, 60, 0};
  cam.far_plane = 5000;
  const ts::Frustum frustum = ts::Frustum::of(cam);
  ts::TessellationSettings settings;
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  std::size_t triangles = 0, culled = 0, partial = 0;
  for (const ts::Surface& s : m.surfaces) {
    const ts::SurfaceResult r = ts::tessellate_surface(ts::prepare_surface(s), cam, frustum, settings, scratch, out);
    INFO(s.name);
    REQUIRE(r.inconsistencies() == 0);
    triangles += r.triangles;
    culled += r.culled != ts::Culled::no;
    partial += r.partial_cells;
  }
  CHECK(triangles > 100000);
  CHECK(culled > 0);
  CHECK(partial > 1000);
}
