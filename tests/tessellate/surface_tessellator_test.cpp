// Per-frame tessellation of trimmed surfaces (tessellate/surface_tessellator.hpp), fixed-seed property tests
// that print their counterexample:
//   - screen-space deviation of surface points from the triangles ≤ the pixel tolerance, trimmed or not;
//   - no triangle outside the trimmed region; the triangulated area of a plate with a hole converges to the
//     exact trimmed area as the tolerance shrinks;
//   - adjacent untrimmed patches with equal step sizes share their boundary vertices (teapot), and do not
//     with unequal ones (the negative control);
//   - culling never removes a patch that has a visible point;
//   - steady-state frames allocate nothing; components from adjacency; OBJ/PLY export.
#include "tessellate/surface_tessellator.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <map>
#include <set>
#include <random>
#include <sstream>

#include "tessellate/components.hpp"
#include "tessellate/mesh_export.hpp"
#include "tessellate/model_format.hpp"
#include "tests/tessellate/random_patch.hpp"
#include "tests/tessellate/trim_shapes.hpp"

namespace ts = frontsteal::tess;
using namespace frontsteal::tess::testing;

namespace {

ts::Camera random_camera(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), dist(2.5, 6.0), fov(0.5, 1.2);
  ts::Camera c;
  glm::dvec3 dir;
  do dir = {unit(rng), unit(rng), unit(rng)};
  while (glm::length(dir) < 0.2 || glm::length(dir) > 1.0);
  c.eye = glm::normalize(dir) * dist(rng);
  c.target = {0.3 * unit(rng), 0.3 * unit(rng), 0.3 * unit(rng)};
  c.up = std::abs(glm::normalize(c.target - c.eye).z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  c.fovy_radians = fov(rng);
  c.width = 640;
  c.height = 480;
  return c;
}

// Farther away (8 to 30 units), aimed beside the patch: it covers a small part of the image, anywhere in it,
// often near an edge or a corner, where the perspective factor of plan_surface matters most.
ts::Camera random_far_camera(std::mt19937_64& rng) {
  ts::Camera c = random_camera(rng);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), dist(8.0, 30.0);
  const double d = dist(rng);
  c.eye = glm::normalize(c.eye) * d;
  const double reach = 0.8 * std::tan(0.5 * c.fovy_radians) * d;
  c.target = glm::dvec3(0.5, 0.5, 0.0) + reach * glm::dvec3(unit(rng), unit(rng), unit(rng));
  c.up = std::abs(glm::normalize(c.target - c.eye).z) > 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
  return c;
}

struct DeviationProbe {
  double worst_px = 0;
  glm::dvec2 at_uv{0.0};
  int samples = 0;
};

// Random points of random triangles: S at the point's (u, v) against the triangle's linear interpolation,
// both projected, where both land inside the viewport and in front of the near plane.
DeviationProbe probe_deviation(const ts::BezierPatch& patch, const ts::TriangleBuffers& tri, const ts::Camera& cam,
                               std::mt19937_64& rng, int samples) {
  DeviationProbe probe;
  if (tri.indices.empty()) return probe;
  std::uniform_int_distribution<std::size_t> pick(0, tri.triangle_count() - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int s = 0; s < samples; ++s) {
    const std::size_t t = pick(rng);
    double a = unit(rng), b = unit(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const double w[3] = {1 - a - b, a, b};
    glm::dvec2 uv(0.0);
    glm::dvec3 linear(0.0);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = tri.indices[3 * t + k];
      uv += w[k] * glm::dvec2(tri.uvs[v]);
      linear += w[k] * glm::dvec3(tri.positions[v]);
    }
    const glm::dvec3 exact = ts::evaluate(patch, uv.x, uv.y).position;
    const glm::dvec3 pe = cam.project(exact), pl = cam.project(linear);
    const auto visible = [&](const glm::dvec3& p) {
      return p.z > cam.near_plane && p.x >= 0 && p.x <= cam.width && p.y >= 0 && p.y <= cam.height;
    };
    if (!visible(pe) || !visible(pl)) continue;
    ++probe.samples;
    const double d = glm::length(glm::dvec2(pe) - glm::dvec2(pl));
    if (d > probe.worst_px) probe.worst_px = d, probe.at_uv = uv;
  }
  return probe;
}

ts::Surface trimmed_random_surface(std::mt19937_64& rng, int du, int dv, bool rational) {
  ts::Surface s;
  s.patch = random_patch(rng, du, dv, rational);
  std::uniform_int_distribution<int> verts(8, 30);
  s.loops.push_back(polyline_loop(random_star(rng, {0.5, 0.5}, 0.3, 0.49, verts(rng), true)));
  s.loops.push_back(polyline_loop(random_star(rng, {0.4, 0.5}, 0.04, 0.1, verts(rng), false)));
  s.loops.push_back(circle_loop({0.62, 0.5}, 0.06, false));
  return s;
}

}  // namespace

TEST_CASE("screen-space deviation stays within the pixel tolerance, trimmed and untrimmed", "[tessellate]") {
  std::mt19937_64 rng(5);
  ts::TessellationSettings settings;
  settings.max_steps = 4096;  // no clamping: the bound alone decides
  settings.max_edge_pixels = 1e9;
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  int probed = 0;
  // Trials 0..119 close up (the patch fills much of the image), 120..359 from afar (a small patch anywhere).
  for (int trial = 0; trial < 360; ++trial) {
    const int du = 1 + trial % 4, dv = 1 + (trial / 4) % 4;
    const bool rational = trial % 3 == 0;
    const bool trimmed = trial % 2 == 0;
    ts::Surface s = trimmed ? trimmed_random_surface(rng, du, dv, rational)
                            : ts::Surface{"", random_patch(rng, du, dv, rational), {}, -1, false};
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    const ts::Camera cam = trial < 120 ? random_camera(rng) : random_far_camera(rng);
    for (double tol : {2.0, 0.5}) {
      settings.pixel_tolerance = tol;
      const ts::SurfaceResult r = ts::tessellate_surface(prepared, cam, ts::Frustum::of(cam), settings, scratch, tri);
      if (r.culled != ts::Culled::no) continue;
      REQUIRE(r.inconsistencies() == 0);
      const DeviationProbe probe = probe_deviation(s.patch, tri, cam, rng, 400);
      probed += probe.samples > 0;
      INFO("trial " << trial << " degree " << du << "x" << dv << (rational ? " rational" : "")
                    << (trimmed ? " trimmed" : "") << ", steps " << r.steps.n_u << "x" << r.steps.n_v << ", tolerance "
                    << tol << " px: worst " << probe.worst_px << " px at (u,v) = (" << probe.at_uv.x << ", "
                    << probe.at_uv.y << ")");
      // float vertex positions add ~1e-7 relative: far below a pixel here.
      CHECK(probe.worst_px <= tol * 1.0001 + 1e-3);
    }
  }
  CHECK(probed > 300);
}

TEST_CASE("negative control: a quarter of the step counts breaks the pixel tolerance", "[tessellate]") {
  std::mt19937_64 rng(6);
  ts::TessellationSettings settings;
  settings.pixel_tolerance = 0.5;
  settings.max_edge_pixels = 1e9;
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  double worst = 0;
  for (int trial = 0; trial < 20; ++trial) {
    ts::Surface s{"", random_patch(rng, 3, 3, false), {}, -1, false};
    const ts::Camera cam = random_camera(rng);
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    ts::SurfacePlan plan = ts::plan_surface(prepared, cam, ts::Frustum::of(cam), settings);
    if (plan.culled != ts::Culled::no) continue;
    plan.steps = {std::max(1, plan.steps.n_u / 4), std::max(1, plan.steps.n_v / 4)};
    std::vector<ts::BernsteinTable> basis;
    ts::tessellate_untrimmed(s.patch, plan.steps, tri, basis);
    worst = std::max(worst, probe_deviation(s.patch, tri, cam, rng, 400).worst_px);
  }
  CHECK(worst > settings.pixel_tolerance);
}

TEST_CASE("a plate with a circular hole: no triangle in the hole, area converges to the exact trimmed area",
          "[tessellate]") {
  ts::Surface plate{"plate", flat_plate(1.0), {}, -1, false};
  plate.loops.push_back(polyline_loop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));  // the domain: dropped as outer loop
  plate.loops.push_back(circle_loop({0.5, 0.5}, 0.25, false));
  const double exact = 1.0 + loop_area(plate.loops[1]);  // the hole's area is negative (clockwise)
  const ts::PreparedSurface prepared = ts::prepare_surface(plate);
  ts::Camera cam;
  cam.eye = {0.5, 0.5, 1.5};
  cam.target = {0.5, 0.5, 0.0};
  cam.up = {0, 1, 0};
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  ts::TessellationSettings settings;
  double previous_error = 1.0;
  for (double tol : {8.0, 2.0, 0.5, 0.125, 0.03}) {
    settings.pixel_tolerance = tol;
    const ts::SurfacePlan plan = ts::plan_surface(prepared, cam, ts::Frustum::of(cam), settings);
    const ts::SurfaceResult r = ts::tessellate_trimmed(prepared, plan, settings, scratch, tri);
    REQUIRE(r.inconsistencies() == 0);
    double area = 0;
    double deepest = 0;  // how far a triangle's centroid reaches into the hole
    for (std::size_t t = 0; t < tri.indices.size(); t += 3) {
      const glm::dvec3 a = tri.positions[tri.indices[t]], b = tri.positions[tri.indices[t + 1]],
                       c = tri.positions[tri.indices[t + 2]];
      area += 0.5 * glm::cross(b - a, c - a).z;  // counter-clockwise seen from +z: positive
      const glm::dvec2 centroid = glm::dvec2((a + b + c) / 3.0);
      deepest = std::max(deepest, 0.25 - glm::length(centroid - glm::dvec2(0.5)));
    }
    const double error = std::abs(area - exact);
    // The trim polyline is inscribed within ε_dom of the curve; the Bézier circle is within 3e-4·r of a circle.
    const double eps_domain = plan.epsilon / (prepared.bounds.len_u + prepared.bounds.len_v);
    INFO("tolerance " << tol << " px: steps " << r.steps.n_u << "x" << r.steps.n_v << ", " << r.trim_points
                      << " trim points, " << r.triangles << " triangles, area " << area << " vs exact " << exact
                      << ", deepest " << deepest);
    CHECK(deepest <= eps_domain + 0.25 * 2.8e-4 + 1e-9);
    CHECK(error <= previous_error * 1.0000001);
    // Inscribed chords within ε_dom of the curve lose at most perimeter · ε_dom of area.
    CHECK(error <= 2 * std::numbers::pi * 0.25 * eps_domain);
    previous_error = error;
  }
  CHECK(previous_error < 1e-4);
}

TEST_CASE("trimmed triangles stay inside their polyline trim region", "[tessellate]") {
  std::mt19937_64 rng(8);
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  ts::TessellationSettings settings;
  for (int trial = 0; trial < 60; ++trial) {
    ts::Surface s{"", flat_plate(1.0), {}, -1, false};
    std::uniform_int_distribution<int> verts(8, 40);
    const auto outer = random_star(rng, {0.5, 0.5}, 0.3, 0.49, verts(rng), true);
    const auto hole = random_star(rng, {0.5, 0.5}, 0.08, 0.2, verts(rng), false);
    s.loops = {polyline_loop(outer), polyline_loop(hole)};
    const double exact = 0.5 * (ts::signed_area2(outer) + ts::signed_area2(hole));
    ts::Camera cam;
    cam.eye = {0.5, 0.5, 1.0 + trial * 0.05};
    cam.target = {0.5, 0.5, 0.0};
    cam.up = {0, 1, 0};
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    const ts::SurfaceResult r = ts::tessellate_surface(prepared, cam, ts::Frustum::of(cam), settings, scratch, tri);
    REQUIRE(r.culled == ts::Culled::no);
    double area = 0;
    int outside = 0;
    const auto inside = [](const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
      bool in = false;
      for (std::size_t k = 0, j = poly.size() - 1; k < poly.size(); j = k++) {
        if ((poly[k].y > p.y) != (poly[j].y > p.y) &&
            p.x < (poly[j].x - poly[k].x) * (p.y - poly[k].y) / (poly[j].y - poly[k].y) + poly[k].x) {
          in = !in;
        }
      }
      return in;
    };
    // Distance from p to the nearest edge of either loop: a sliver along a trim edge, its vertices on the edge
    // and stored as float (u, v), may have its centroid a rounding beyond the edge; a misplaced triangle's
    // centroid lies well away from both loops.
    const auto to_boundary = [&](glm::dvec2 p) {
      double d = 1e300;
      for (const auto* poly : {&outer, &hole}) {
        for (std::size_t k = 0, j = poly->size() - 1; k < poly->size(); j = k++) {
          const glm::dvec2 e = (*poly)[k] - (*poly)[j];
          const double t = std::clamp(glm::dot(p - (*poly)[j], e) / glm::dot(e, e), 0.0, 1.0);
          d = std::min(d, glm::length(p - ((*poly)[j] + t * e)));
        }
      }
      return d;
    };
    double worst_outside = 0;
    for (std::size_t t = 0; t < tri.indices.size(); t += 3) {
      const glm::dvec2 a = tri.uvs[tri.indices[t]], b = tri.uvs[tri.indices[t + 1]], c = tri.uvs[tri.indices[t + 2]];
      area += 0.5 * ts::detail::cross2(a, b, c);
      const glm::dvec2 centroid = (a + b + c) / 3.0;
      if (!inside(outer, centroid) || inside(hole, centroid)) {
        const double d = to_boundary(centroid);
        worst_outside = std::max(worst_outside, d);
        if (d > 1e-6) ++outside;
      }
    }
    INFO("trial " << trial << ": steps " << r.steps.n_u << "x" << r.steps.n_v << ", " << r.triangles
                  << " triangles, area " << area << " vs " << exact << "; centroids outside by at most "
                  << worst_outside);
    CHECK(outside == 0);
    CHECK(area == Approx(exact).margin(1e-5));  // polyline trims: the triangles tile the region exactly
    CHECK(worst_outside < 1e-6);
  }
}

TEST_CASE("culling never removes a patch with a visible point", "[tessellate]") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0), place(-3.0, 3.0);
  ts::TessellationSettings settings;
  int culled_frustum = 0, culled_back = 0;
  for (int trial = 0; trial < 400; ++trial) {
    ts::Surface s{"", random_patch(rng, 1 + trial % 3, 1 + trial % 4, trial % 2 == 0), {}, -1, true};
    const glm::dvec3 offset{place(rng), place(rng), place(rng)};
    // Every other patch a gently bent sheet (a narrow cone of normals, around ±z): the back-face test can fire.
    if (trial % 2) {
      for (int i = 0; i <= s.patch.degree_u; ++i) {
        for (int j = 0; j <= s.patch.degree_v; ++j) {
          const glm::dvec3 p{2.0 * i / s.patch.degree_u - 1 + 0.1 * (unit(rng) - 0.5),
                             2.0 * j / s.patch.degree_v - 1 + 0.1 * (unit(rng) - 0.5), 0.3 * (unit(rng) - 0.5)};
          s.patch.set(i, j, p, s.patch.weight(i, j));
        }
      }
    }
    for (glm::dvec4& h : s.patch.control) {
      const glm::dvec3 p = glm::dvec3(h) / h.w * 0.3 + offset;
      h = glm::dvec4(p * h.w, h.w);
    }
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    const ts::Camera cam = random_camera(rng);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    const ts::SurfacePlan plan = ts::plan_surface(prepared, cam, frustum, settings);
    if (plan.culled == ts::Culled::no) continue;
    (plan.culled == ts::Culled::frustum ? culled_frustum : culled_back)++;
    // A culled patch must have no point inside the frustum that faces the eye (frustum culling: none inside).
    for (int k = 0; k < 2000; ++k) {
      const ts::SurfacePoint sp = ts::evaluate(s.patch, unit(rng), unit(rng));
      const bool in_view = frustum.contains(sp.position);
      const bool front = glm::dot(sp.normal, cam.eye - sp.position) > 0;
      INFO("trial " << trial << " culled by " << (plan.culled == ts::Culled::frustum ? "frustum" : "back face")
                    << " but the point (" << sp.position.x << ", " << sp.position.y << ", " << sp.position.z
                    << ") is visible");
      REQUIRE_FALSE((in_view && (plan.culled == ts::Culled::frustum || front)));
    }
  }
  // Both tests must actually fire for this to mean anything.
  CHECK(culled_frustum > 20);
  CHECK(culled_back > 10);
}

namespace {

ts::Model teapot() { return ts::load_model(std::string(FRONTSTEAL_DATA_DIR) + "/models/teapot.fsm"); }

// Patch edge e (0: v=0, 1: u=1, 2: v=1, 3: u=0) as its control points.
std::vector<glm::dvec3> edge_controls(const ts::BezierPatch& p, int e) {
  std::vector<glm::dvec3> out;
  const int n = (e % 2 == 0) ? p.degree_u : p.degree_v;
  for (int k = 0; k <= n; ++k) {
    if (e == 0) out.push_back(p.point(k, 0));
    if (e == 1) out.push_back(p.point(p.degree_u, k));
    if (e == 2) out.push_back(p.point(k, p.degree_v));
    if (e == 3) out.push_back(p.point(0, k));
  }
  return out;
}

// Grid vertices of edge e from an untrimmed tessellation with `steps`.
std::vector<glm::dvec3> edge_vertices(const ts::TriangleBuffers& b, ts::StepSizes steps, int e) {
  std::vector<glm::dvec3> out;
  const int n = (e % 2 == 0) ? steps.n_u : steps.n_v;
  const auto at = [&](int i, int j) {
    return glm::dvec3(b.positions[static_cast<std::size_t>(i * (steps.n_v + 1) + j)]);
  };
  for (int k = 0; k <= n; ++k) {
    if (e == 0) out.push_back(at(k, 0));
    if (e == 1) out.push_back(at(steps.n_u, k));
    if (e == 2) out.push_back(at(k, steps.n_v));
    if (e == 3) out.push_back(at(0, k));
  }
  return out;
}

// Over all pairs of teapot patch edges with equal control points (forward or reversed), the largest distance
// between matching boundary vertices, with patch k tessellated at steps_of(k).
double worst_seam_gap(const ts::Model& m, const std::function<ts::StepSizes(std::size_t)>& steps_of,
                      int* shared_edges) {
  std::vector<ts::TriangleBuffers> buffers(m.surfaces.size());
  std::vector<ts::BernsteinTable> basis;
  for (std::size_t k = 0; k < m.surfaces.size(); ++k)
    ts::tessellate_untrimmed(m.surfaces[k].patch, steps_of(k), buffers[k], basis);
  double worst = 0;
  *shared_edges = 0;
  for (std::size_t a = 0; a < m.surfaces.size(); ++a) {
    for (std::size_t b = a + 1; b < m.surfaces.size(); ++b) {
      for (int ea = 0; ea < 4; ++ea) {
        for (int eb = 0; eb < 4; ++eb) {
          const auto ca = edge_controls(m.surfaces[a].patch, ea), cb = edge_controls(m.surfaces[b].patch, eb);
          if (ca.size() != cb.size()) continue;
          const bool forward =
              std::equal(ca.begin(), ca.end(), cb.begin(), [](auto x, auto y) { return glm::length(x - y) < 1e-9; });
          const bool backward =
              std::equal(ca.begin(), ca.end(), cb.rbegin(), [](auto x, auto y) { return glm::length(x - y) < 1e-9; });
          if (!forward && !backward) continue;
          if (glm::length(ca.front() - ca.back()) < 1e-9 && glm::length(ca[1] - ca[0]) < 1e-9)
            continue;  // collapsed edge
          ++*shared_edges;
          auto va = edge_vertices(buffers[a], steps_of(a), ea), vb = edge_vertices(buffers[b], steps_of(b), eb);
          if (backward) std::reverse(vb.begin(), vb.end());
          // Every vertex on one side must have a vertex on the other side at the same place.
          for (const glm::dvec3& p : va) {
            double nearest = 1e30;
            for (const glm::dvec3& q : vb) nearest = std::min(nearest, glm::length(p - q));
            worst = std::max(worst, nearest);
          }
        }
      }
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("teapot: adjacent untrimmed patches with equal steps share their boundary vertices", "[tessellate]") {
  const ts::Model m = teapot();
  REQUIRE(m.surfaces.size() == 32);
  int shared = 0;
  const double gap = worst_seam_gap(
      m,
      [](std::size_t) {
        return ts::StepSizes{7, 7};
      },
      &shared);
  INFO(shared << " shared edges, worst gap " << gap);
  CHECK(shared >= 40);
  CHECK(gap < 1e-5);  // float vertex positions
  // Negative control: unequal step counts across a seam leave vertices with no partner (a crack).
  const double cracked = worst_seam_gap(
      m,
      [](std::size_t k) {
        return ts::StepSizes{k % 2 ? 7 : 8, k % 2 ? 7 : 8};
      },
      &shared);
  CHECK(cracked > 1e-3);
}

TEST_CASE("components from adjacency: patches sharing edges join, others stay apart", "[tessellate]") {
  ts::Model m;
  for (int k = 0; k < 3; ++k) {
    ts::Surface s{"plate" + std::to_string(k), flat_plate(1.0), {}, -1, false};
    const glm::dvec3 shift = k < 2 ? glm::dvec3(k, 0, 0) : glm::dvec3(5, 5, 0);  // 0 and 1 share the edge x = 1
    for (glm::dvec4& h : s.patch.control) h += glm::dvec4(shift, 0.0);
    m.surfaces.push_back(s);
  }
  CHECK(ts::assign_components(m, 1e-6) == 2);
  CHECK(m.surfaces[0].component == m.surfaces[1].component);
  CHECK(m.surfaces[2].component != m.surfaces[0].component);
  // The teapot: its body is one piece; the handle and the spout pierce the body without sharing an edge.
  ts::Model pot = teapot();
  const int n = ts::assign_components(pot, 1e-6);
  std::map<std::string, std::set<int>> by_part;
  for (const ts::Surface& s : pot.surfaces) by_part[s.name.substr(0, s.name.find('_'))].insert(s.component);
  INFO(n << " components");
  CHECK(by_part["handle"].size() == 1);
  CHECK(by_part["spout"].size() == 1);
  CHECK(*by_part["handle"].begin() != *by_part["spout"].begin());
  CHECK(*by_part["body"].begin() == *by_part["rim"].begin());
}

TEST_CASE("steady-state frames reuse their buffers, and OBJ and PLY export", "[tessellate]") {
  const ts::Model m = teapot();
  std::vector<ts::PreparedSurface> prepared;
  for (const ts::Surface& s : m.surfaces) prepared.push_back(ts::prepare_surface(s));
  ts::Camera cam;
  cam.eye = {8, -6, 5};
  cam.target = {0, 0, 1.5};
  std::vector<ts::TriangleBuffers> buffers(m.surfaces.size());
  ts::TessellationScratch scratch;
  ts::TessellationSettings settings;
  const auto frame = [&] {
    for (std::size_t k = 0; k < prepared.size(); ++k)
      ts::tessellate_surface(prepared[k], cam, ts::Frustum::of(cam), settings, scratch, buffers[k]);
  };
  frame();
  std::vector<const void*> before;
  for (const auto& b : buffers) before.push_back(b.positions.data());
  frame();
  for (std::size_t k = 0; k < buffers.size(); ++k) CHECK(buffers[k].positions.data() == before[k]);

  std::vector<ts::MeshPart> parts;
  std::size_t triangles = 0, vertices = 0;
  for (std::size_t k = 0; k < buffers.size(); ++k) {
    parts.push_back({m.surfaces[k].name, &buffers[k]});
    triangles += buffers[k].triangle_count();
    vertices += buffers[k].positions.size();
  }
  std::ostringstream obj, ply;
  ts::write_obj(obj, parts);
  ts::write_ply(ply, parts);
  const std::string o = obj.str(), p = ply.str();
  std::size_t faces = 0;
  for (std::size_t at = o.find("\nf "); at != std::string::npos; at = o.find("\nf ", at + 1)) ++faces;
  CHECK(faces == triangles);
  CHECK(p.find("element vertex " + std::to_string(vertices)) != std::string::npos);
  CHECK(p.find("element face " + std::to_string(triangles)) != std::string::npos);
  const std::size_t header = p.find("end_header\n") + 11;
  CHECK(p.size() - header == vertices * 32 + triangles * 17);
  CHECK_THROWS_WITH(ts::write_mesh_file("frontsteal-test.stl", parts), Catch::Contains(".obj or .ply"));
}

TEST_CASE("the cost estimate grows with screen size and trimming, and is small when culled", "[tessellate]") {
  ts::Surface plain{"plain", flat_plate(1.0), {}, -1, false};
  ts::Surface holed = plain;
  holed.loops = {polyline_loop({{0, 0}, {1, 0}, {1, 1}, {0, 1}}), circle_loop({0.5, 0.5}, 0.25, false)};
  const ts::PreparedSurface p_plain = ts::prepare_surface(plain), p_holed = ts::prepare_surface(holed);
  ts::TessellationSettings settings;
  const auto cost_from = [&](const ts::PreparedSurface& p, double height) {
    ts::Camera cam;
    cam.eye = {0.5, 0.5, height};
    cam.target = {0.5, 0.5, 0.0};
    cam.up = {0, 1, 0};
    return ts::estimate_cost(p, ts::plan_surface(p, cam, ts::Frustum::of(cam), settings), settings);
  };
  CHECK(cost_from(p_plain, 0.8) > cost_from(p_plain, 8.0));  // closer: larger on screen, more steps
  CHECK(cost_from(p_holed, 2.0) > cost_from(p_plain, 2.0));  // trim work adds to the grid's
  ts::Camera away;
  away.eye = {0.5, 0.5, 2.0};
  away.target = {0.5, 0.5, 4.0};  // looking away: frustum-culled
  away.up = {0, 1, 0};
  const ts::SurfacePlan culled = ts::plan_surface(p_plain, away, ts::Frustum::of(away), settings);
  CHECK(culled.culled == ts::Culled::frustum);
  CHECK(ts::estimate_cost(p_plain, culled, settings) < 0.1 * cost_from(p_plain, 2.0));
}

TEST_CASE("one scratch through a mix of surfaces gives the bytes a fresh scratch gives", "[tessellate]") {
  // The trimmed path keeps grid-line tables while (degree, steps) repeat; untrimmed grids (double and float) and
  // trimmed surfaces of other degrees and steps in between must never leave them stale.
  std::mt19937_64 rng(21);
  ts::TessellationScratch shared;
  ts::TriangleBuffers out, fresh_out;
  for (int trial = 0; trial < 60; ++trial) {
    const int du = 1 + trial % 4, dv = 1 + (trial / 3) % 4;
    const bool trimmed = trial % 3 != 1;
    ts::Surface s = trimmed ? trimmed_random_surface(rng, du, dv, trial % 5 == 0)
                            : ts::Surface{"", random_patch(rng, du, dv, false), {}, -1, false};
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    ts::TessellationSettings settings;
    ts::SurfacePlan plan;
    plan.epsilon = 1e-3;
    plan.edge_length = 1e9;
    plan.steps = {2 + trial % 5, 2 + (trial / 2) % 5};  // steps repeat, degrees change between them
    plan.single_precision = trial % 2 == 0;
    ts::TessellationScratch fresh;
    ts::tessellate_planned(prepared, plan, settings, shared, out);
    ts::tessellate_planned(prepared, plan, settings, fresh, fresh_out);
    INFO("trial " << trial << ": degree " << du << "x" << dv << (trimmed ? " trimmed" : "") << ", steps "
                  << plan.steps.n_u << "x" << plan.steps.n_v);
    CHECK(out.positions == fresh_out.positions);
    CHECK(out.indices == fresh_out.indices);
  }
}

TEST_CASE("trimmed grids in single precision: only grid corners differ, within the float bound", "[tessellate]") {
  // The trimmed path evaluates its grid corners by the float kernel where plan.single_precision allows, as the
  // untrimmed grid does. Against the double path: the same vertices in the same order ((u, v) and indices equal),
  // trim points bit-identical (always in double), grid corners within float_row_error_bound, the same audit.
  std::mt19937_64 rng(33);
  ts::TessellationScratch scratch;
  ts::TriangleBuffers exact, fast;
  ts::TessellationSettings settings;
  int corners = 0, trim_points = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const int du = 1 + trial % 4, dv = 1 + (trial / 4) % 4;
    const ts::Surface s = trimmed_random_surface(rng, du, dv, trial % 3 == 0);
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    ts::SurfacePlan plan;
    plan.epsilon = 1e-3;
    plan.edge_length = 0.05;
    plan.steps = {3 + trial % 29, 3 + (trial * 7) % 31};
    plan.single_precision = false;
    const ts::SurfaceResult r_exact = ts::tessellate_planned(prepared, plan, settings, scratch, exact);
    plan.single_precision = true;
    const ts::SurfaceResult r_fast = ts::tessellate_planned(prepared, plan, settings, scratch, fast);
    INFO("trial " << trial << ": degree " << du << "x" << dv << ", steps " << plan.steps.n_u << "x" << plan.steps.n_v);
    REQUIRE(r_exact.inconsistencies() == 0);
    CHECK(r_fast.inconsistencies() == 0);
    CHECK(r_fast.triangles == r_exact.triangles);
    REQUIRE(fast.uvs == exact.uvs);
    CHECK(fast.indices == exact.indices);
    const double bound = ts::float_row_error_bound(s.patch) + 1.2e-7 * 4.0;  // plus one float rounding
    for (std::size_t k = 0; k < exact.positions.size(); ++k) {
      const glm::vec2 uv = exact.uvs[k];
      const auto on_line = [](float t, int n) { return static_cast<float>(std::round(t * n)) / n == t; };
      const bool corner = on_line(uv.x, plan.steps.n_u) && on_line(uv.y, plan.steps.n_v);
      if (!corner) {
        CHECK(fast.positions[k] == exact.positions[k]);
        CHECK(fast.normals[k] == exact.normals[k]);
        ++trim_points;
        continue;
      }
      corners += fast.positions[k] != exact.positions[k];
      CHECK(glm::length(fast.positions[k] - exact.positions[k]) <= bound);
      CHECK(glm::dot(fast.normals[k], exact.normals[k]) > std::cos(1e-3));
    }
  }
  CHECK(corners > 1000);  // corners that differ: the float path did run
  CHECK(trim_points > 1000);
}

TEST_CASE("trimmed grids in single precision: a trim point on a grid corner sits exactly where the corner does",
          "[tessellate]") {
  // A trim edge through grid corners (here the diagonal of a square grid) puts trim points exactly on them; the
  // cells beside such a point use the corner's vertex, the partial cells the trim point's. Both must be at the
  // same position, or a crack as wide as the float error opens along the cell edge between them.
  std::mt19937_64 rng(35);
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  ts::TessellationSettings settings;
  int shared_places = 0;
  for (int trial = 0; trial < 12; ++trial) {
    ts::Surface s;
    s.patch = random_patch(rng, 1 + trial % 3, 1 + (trial / 3) % 3, trial % 2 == 1);
    s.loops.push_back(polyline_loop({{0.05, 0.05}, {0.95, 0.95}, {0.05, 0.95}}));
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    ts::SurfacePlan plan;
    plan.epsilon = 1e-3;
    plan.edge_length = 1e9;
    plan.steps = {10 + 2 * trial, 10 + 2 * trial};
    plan.single_precision = true;
    const ts::SurfaceResult r = ts::tessellate_planned(prepared, plan, settings, scratch, tri);
    REQUIRE(r.inconsistencies() == 0);
    std::map<std::pair<float, float>, std::vector<std::size_t>> by_uv;
    for (std::size_t k = 0; k < tri.uvs.size(); ++k) by_uv[{tri.uvs[k].x, tri.uvs[k].y}].push_back(k);
    for (const auto& [uv, vertices] : by_uv) {
      if (vertices.size() < 2) continue;
      ++shared_places;
      for (std::size_t k : vertices) {
        INFO("trial " << trial << ", (u, v) = (" << uv.first << ", " << uv.second << ")");
        CHECK(tri.positions[k] == tri.positions[vertices[0]]);
      }
    }
  }
  CHECK(shared_places > 50);  // the diagonal did pass through corners
}

TEST_CASE("long trim polylines in few cells: large pieces get the constrained triangulation, audited like the rest",
          "[tessellate]") {
  std::mt19937_64 rng(27);
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  ts::TessellationSettings settings;
  settings.max_steps = 2;  // a 2×2 grid at most: each cell holds a quarter of each polyline
  ts::Camera cam;
  cam.eye = {0.5, 0.5, 2.0};
  cam.target = {0.5, 0.5, 0.0};
  cam.up = {0, 1, 0};
  for (int trial = 0; trial < 10; ++trial) {
    ts::Surface s{"", flat_plate(1.0), {}, -1, false};
    const auto outer = random_star(rng, {0.5, 0.5}, 0.3, 0.49, 1600 + 400 * trial, true);
    const auto hole = random_star(rng, {0.5, 0.5}, 0.08, 0.2, 1200, false);
    s.loops = {polyline_loop(outer), polyline_loop(hole)};
    const double exact = 0.5 * (ts::signed_area2(outer) + ts::signed_area2(hole));
    const ts::PreparedSurface prepared = ts::prepare_surface(s);
    settings.planted_defect = ts::PlantedDefect::none;
    const ts::SurfaceResult r = ts::tessellate_surface(prepared, cam, ts::Frustum::of(cam), settings, scratch, tri);
    double area = 0;
    for (std::size_t t = 0; t < tri.indices.size(); t += 3) {
      area +=
          0.5 * ts::detail::cross2(tri.uvs[tri.indices[t]], tri.uvs[tri.indices[t + 1]], tri.uvs[tri.indices[t + 2]]);
    }
    INFO("trial " << trial << ": steps " << r.steps.n_u << "x" << r.steps.n_v << ", " << r.partial_cells
                  << " partial cells, " << r.constrained_pieces << " pieces by the constrained triangulation, "
                  << r.triangles << " triangles, area " << area << " vs " << exact);
    CHECK(r.constrained_pieces > 0);
    CHECK(r.inconsistencies() == 0);
    CHECK(area == Approx(exact).margin(1e-5));
    // Negative control: the planted defect drops each piece's first triangle, on this path as on ear clipping's.
    settings.planted_defect = ts::PlantedDefect::drop_ear;
    const ts::SurfaceResult planted =
        ts::tessellate_surface(prepared, cam, ts::Frustum::of(cam), settings, scratch, tri);
    CHECK(planted.constrained_pieces > 0);
    CHECK(planted.tiling_violations > 0);
  }
}
