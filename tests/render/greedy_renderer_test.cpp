// Headless OpenGL rendering and greedy rendering (render/): the image is not empty and covers the pixels the
// tessellated triangles cover (checked against a CPU rasterization of the same triangles, with a shifted view
// as negative control), the greedy run's statistics add up, and lagging frames stay close to synchronized ones.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "render/greedy_renderer.hpp"
#include "render/headless_gl.hpp"
#include "render/triangle_renderer.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/components.hpp"
#include "tessellate/scene_generator.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

ts::Model teapot() {
  ts::Model m = ts::load_scene("teapot", FRONTSTEAL_DATA_DIR);
  ts::assign_components(m, 1e-6);
  return m;
}

// Pixels whose centre lies inside some triangle of the tessellation for `tessellated_for`, projected with `view`.
std::vector<char> cpu_coverage(const ts::Model& m, const ts::Camera& tessellated_for, const ts::Camera& view) {
  std::vector<char> mask(static_cast<std::size_t>(view.width) * view.height, 0);
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  const ts::Frustum frustum = ts::Frustum::of(tessellated_for);
  for (const ts::Surface& s : m.surfaces) {
    ts::tessellate_surface(ts::prepare_surface(s), tessellated_for, frustum, {}, scratch, out);
    for (std::size_t t = 0; t + 2 < out.indices.size(); t += 3) {
      glm::dvec3 p[3];
      for (int k = 0; k < 3; ++k) p[k] = view.project(glm::dvec3(out.positions[out.indices[t + k]]));
      if (p[0].z <= 0 || p[1].z <= 0 || p[2].z <= 0) continue;
      const double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
      if (area == 0) continue;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
      const int x1 = std::min(view.width - 1, static_cast<int>(std::ceil(std::max({p[0].x, p[1].x, p[2].x}))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
      const int y1 = std::min(view.height - 1, static_cast<int>(std::ceil(std::max({p[0].y, p[1].y, p[2].y}))));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const double cx = x + 0.5, cy = y + 0.5;
          double w[3];
          for (int k = 0; k < 3; ++k) {
            const glm::dvec3& a = p[k];
            const glm::dvec3& b = p[(k + 1) % 3];
            w[k] = ((b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x)) * (area > 0 ? 1 : -1);
          }
          if (w[0] >= 0 && w[1] >= 0 && w[2] >= 0)
            mask[static_cast<std::size_t>(view.height - 1 - y) * view.width + x] = 1;
        }
      }
    }
  }
  return mask;
}

double intersection_over_union(const rd::Image& image, const std::vector<char>& mask) {
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    const std::uint8_t* px = &image.rgb[i * 3];
    bool drawn = false;
    for (int c = 0; c < 3; ++c) drawn = drawn || std::abs(px[c] - rd::TriangleRenderer::kBackground[c]) > 2;
    both += drawn && mask[i];
    either += drawn || mask[i];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / either;
}

}  // namespace

TEST_CASE("a headless frame of the teapot covers exactly the pixels its triangles cover") {
  const ts::Model m = teapot();
  const ts::Camera cam = ts::camera_on(ts::CameraPathKind::orbit, ts::model_box(m), 3, 24, 160, 96);
  rd::HeadlessGL gl(cam.width, cam.height);
  INFO(gl.description());
  gl.make_current();
  std::uint64_t triangles = 0;
  const rd::Image image = rd::render_synchronized(m, cam, {}, &triangles);
  gl.release();
  CHECK(triangles > 1000);
  const std::size_t covered = rd::covered_pixels(image, rd::TriangleRenderer::kBackground);
  const double fraction = static_cast<double>(covered) / (cam.width * cam.height);
  CHECK(fraction > 0.05);  // not empty …
  CHECK(fraction < 0.9);   // … and not everything
  const double iou = intersection_over_union(image, cpu_coverage(m, cam, cam));
  CHECK(iou > 0.97);
  // Negative control: the same comparison against the view of a later orbit frame must fail.
  const ts::Camera other = ts::camera_on(ts::CameraPathKind::orbit, ts::model_box(m), 6, 24, 160, 96);
  CHECK(intersection_over_union(image, cpu_coverage(m, other, other)) < 0.9);
}

TEST_CASE("greedy rendering with the null renderer: statistics add up") {
  const ts::Model m = teapot();
  rd::GreedyOptions o;
  o.null_renderer = true;
  o.updates = 40;
  o.display_rate = 200;
  o.path = ts::CameraPathKind::orbit;
  const rd::GreedyStats st = rd::run_greedy(m, o);
  CHECK(st.updates == 40);
  REQUIRE(st.per_update.size() == 40);
  CHECK(st.tessellation_frames >= 1);
  CHECK(st.mean_triangles > 0);
  CHECK(st.mean_lag >= 0);
  CHECK(st.max_lag < 40);
  CHECK(st.quality.empty());  // no images without a renderer
  for (std::size_t u = 1; u < st.per_update.size(); ++u)
    CHECK(st.per_update[u].at_seconds >= st.per_update[u - 1].at_seconds);
}

TEST_CASE("greedy rendering reports the tessellation audit, and counts a planted defect") {
  ts::Model m = ts::load_scene("plant:300", FRONTSTEAL_DATA_DIR);
  ts::assign_components(m, 1e-6);
  rd::GreedyOptions o;
  o.null_renderer = true;
  o.updates = 12;
  o.display_rate = 200;
  const rd::GreedyStats clean = rd::run_greedy(m, o);
  CHECK(clean.tessellation_frames >= 1);
  CHECK(clean.tessellation_inconsistencies == 0);
  o.settings.planted_defect = ts::PlantedDefect::drop_ear;  // negative control
  const rd::GreedyStats planted = rd::run_greedy(m, o);
  CHECK(planted.tessellation_inconsistencies > 0);
}

TEST_CASE("greedy rendering with OpenGL: lagging frames stay close to synchronized ones") {
  ts::Model m = ts::load_scene("plant:80", FRONTSTEAL_DATA_DIR);
  rd::GreedyOptions o;
  o.updates = 24;
  o.display_rate = 60;
  o.width = 160;
  o.height = 96;
  o.samples = 2;
  o.path = ts::CameraPathKind::orbit;
  const rd::GreedyStats st = rd::run_greedy(m, o);
  REQUIRE(st.quality.size() == 2);
  for (const rd::QualitySample& q : st.quality) {
    CHECK(q.psnr_db > 20);
    CHECK(q.ssim > 0.8);
  }
  CHECK(st.renderer.find("OpenGL") != std::string::npos);
}

TEST_CASE("single-threaded greedy rendering keeps to the §5.3 budget rule") {
  const ts::Model m = teapot();
  rd::GreedyOptions o;
  o.null_renderer = true;
  o.single_thread = true;
  o.updates = 30;
  o.display_rate = 100;
  const rd::GreedyStats st = rd::run_greedy(m, o);
  CHECK(st.tessellation_frames >= 1);
  for (const rd::UpdateRecord& r : st.per_update) {
    CHECK(r.budget_ms <= 10.0 + 1e-9);  // at most 1/R
    CHECK(r.budget_ms >= 0);
  }
}
