// glu_reference_benchmark — frontsteal's tessellator against GLU's NURBS tessellator (the SGI Sample
// Implementation in Debian's libglu1-mesa), single thread, the same patches at matched grids.
//
// GLU runs in GLU_NURBS_TESSELLATOR mode (no GL context) with GLU_DOMAIN_DISTANCE sampling: U_STEP = V_STEP
// = n samples per unit parameter, the same uniform n × n grid as ours. Both sides produce positions and
// normals into memory: ours into TriangleBuffers, GLU's through its BEGIN/VERTEX/NORMAL/END callbacks into a
// vector. Trims are polylines on both sides (gluPwlCurve), as GLU is unreliable with high-degree NURBS trims.
// Counters: triangles per second ("tri/s", per core), triangles per patch.
// A third group compares triangle counts at equal screen tolerance: GLU_PARAMETRIC_ERROR with the camera's
// sampling matrices against our deviation bound, both at the same pixel tolerance.
#include <GL/glu.h>
#include <benchmark/benchmark.h>

#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "tessellate/model_format.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;

namespace {

ts::Model& teapot() {
  static ts::Model m = ts::load_model(std::string(FRONTSTEAL_DATA_DIR) + "/models/teapot.fsm");
  return m;
}

// A bicubic plate, gently curved, with a circular hole as a 64-segment polyline (clockwise) and the domain as
// its outer loop.
ts::Surface& holed_patch() {
  static ts::Surface s = [] {
    ts::Surface out;
    out.name = "holed";
    out.patch = ts::BezierPatch(3, 3);
    for (int i = 0; i <= 3; ++i) {
      for (int j = 0; j <= 3; ++j) out.patch.set(i, j, {i / 3.0, j / 3.0, 0.2 * std::sin(i + 0.5 * j)});
    }
    ts::TrimLoop domain;
    const glm::dvec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 4; ++k) domain.segments.push_back({{corners[k], corners[(k + 1) % 4]}});
    ts::TrimLoop hole;
    constexpr int kSegments = 64;
    for (int k = 0; k < kSegments; ++k) {
      const double a0 = -2 * M_PI * k / kSegments, a1 = -2 * M_PI * (k + 1) / kSegments;
      hole.segments.push_back({{{0.5 + 0.3 * std::cos(a0), 0.5 + 0.3 * std::sin(a0)},
                                {0.5 + 0.3 * std::cos(a1), 0.5 + 0.3 * std::sin(a1)}}});
    }
    hole.segments.back().control.back() = hole.segments.front().control.front();
    out.loops = {domain, hole};
    return out;
  }();
  return s;
}

// GLU output, stored like ours (positions and normals as floats).
struct GluSink {
  std::vector<float> positions, normals;
  std::size_t triangles = 0;
  std::size_t primitive_vertices = 0;
  GLenum type = 0;
};

extern "C" {
static void GLAPIENTRY on_begin(GLenum type, void* data) {
  auto* s = static_cast<GluSink*>(data);
  s->type = type;
  s->primitive_vertices = 0;
}
static void GLAPIENTRY on_vertex(GLfloat* v, void* data) {
  auto* s = static_cast<GluSink*>(data);
  s->positions.insert(s->positions.end(), v, v + 3);
  ++s->primitive_vertices;
}
static void GLAPIENTRY on_normal(GLfloat* n, void* data) {
  auto* s = static_cast<GluSink*>(data);
  s->normals.insert(s->normals.end(), n, n + 3);
}
static void GLAPIENTRY on_end(void* data) {
  auto* s = static_cast<GluSink*>(data);
  const std::size_t n = s->primitive_vertices;
  if (s->type == GL_TRIANGLES)
    s->triangles += n / 3;
  else if (n >= 3 && (s->type == GL_TRIANGLE_STRIP || s->type == GL_TRIANGLE_FAN || s->type == GL_QUAD_STRIP))
    s->triangles += n - 2;
}
static void GLAPIENTRY on_error(GLenum code) {
  std::fprintf(stderr, "GLU NURBS error %u: %s\n", code, gluErrorString(code));
}
}

struct Glu {
  GLUnurbs* nurbs = gluNewNurbsRenderer();
  GluSink sink;
  Glu() {
    gluNurbsProperty(nurbs, GLU_NURBS_MODE, GLU_NURBS_TESSELLATOR);
    gluNurbsCallback(nurbs, GLU_NURBS_BEGIN_DATA, reinterpret_cast<_GLUfuncptr>(on_begin));
    gluNurbsCallback(nurbs, GLU_NURBS_VERTEX_DATA, reinterpret_cast<_GLUfuncptr>(on_vertex));
    gluNurbsCallback(nurbs, GLU_NURBS_NORMAL_DATA, reinterpret_cast<_GLUfuncptr>(on_normal));
    gluNurbsCallback(nurbs, GLU_NURBS_END_DATA, reinterpret_cast<_GLUfuncptr>(on_end));
    gluNurbsCallback(nurbs, GLU_NURBS_ERROR, reinterpret_cast<_GLUfuncptr>(on_error));
    gluNurbsCallbackData(nurbs, &sink);
  }
  ~Glu() { gluDeleteNurbsRenderer(nurbs); }
  // Tessellates every surface (into a sink cleared per surface, as ours reuses its buffers); triangles made.
  std::size_t draw_all(const std::vector<ts::Surface>& surfaces) {
    std::size_t triangles = 0;
    for (const ts::Surface& s : surfaces) {
      sink.positions.clear();
      sink.normals.clear();
      sink.triangles = 0;
      draw(s);
      triangles += sink.triangles;
    }
    return triangles;
  }
  void domain_distance(int steps) {
    gluNurbsProperty(nurbs, GLU_SAMPLING_METHOD, GLU_DOMAIN_DISTANCE);
    gluNurbsProperty(nurbs, GLU_U_STEP, static_cast<GLfloat>(steps));
    gluNurbsProperty(nurbs, GLU_V_STEP, static_cast<GLfloat>(steps));
  }
  void screen_error(float pixels, const ts::Camera& cam) {
    gluNurbsProperty(nurbs, GLU_AUTO_LOAD_MATRIX, GL_FALSE);
    gluNurbsProperty(nurbs, GLU_SAMPLING_METHOD, GLU_PARAMETRIC_ERROR);
    gluNurbsProperty(nurbs, GLU_PARAMETRIC_TOLERANCE, pixels);
    const glm::mat4 view(cam.view()), proj(cam.projection());
    const GLint viewport[4] = {0, 0, cam.width, cam.height};
    gluLoadSamplingMatrices(nurbs, glm::value_ptr(view), glm::value_ptr(proj), viewport);
  }
  // One rational Bézier patch as a NURBS surface (knots 0^(m+1) 1^(m+1)); trims as polylines.
  void draw(const ts::Surface& s) {
    const ts::BezierPatch& p = s.patch;
    std::vector<GLfloat> uknots, vknots, ctl;
    for (int k = 0; k <= p.degree_u; ++k) uknots.push_back(0);
    for (int k = 0; k <= p.degree_u; ++k) uknots.push_back(1);
    for (int k = 0; k <= p.degree_v; ++k) vknots.push_back(0);
    for (int k = 0; k <= p.degree_v; ++k) vknots.push_back(1);
    // GLU indexes control points as ctl[i * u_stride + j * v_stride].
    for (int i = 0; i <= p.degree_u; ++i) {
      for (int j = 0; j <= p.degree_v; ++j) {
        const glm::dvec4& h = p.homogeneous(i, j);
        ctl.insert(ctl.end(), {static_cast<float>(h.x), static_cast<float>(h.y), static_cast<float>(h.z),
                               static_cast<float>(h.w)});
      }
    }
    gluBeginSurface(nurbs);
    gluNurbsSurface(nurbs, static_cast<GLint>(uknots.size()), uknots.data(), static_cast<GLint>(vknots.size()),
                    vknots.data(), 4 * (p.degree_v + 1), 4, ctl.data(), p.degree_u + 1, p.degree_v + 1,
                    GL_MAP2_VERTEX_4);
    for (const ts::TrimLoop& loop : s.loops) {
      std::vector<GLfloat> pts;
      for (const ts::TrimSegment& seg : loop.segments)
        pts.insert(pts.end(), {static_cast<float>(seg.control.front().x), static_cast<float>(seg.control.front().y)});
      pts.insert(pts.end(), {pts[0], pts[1]});
      gluBeginTrim(nurbs);
      gluPwlCurve(nurbs, static_cast<GLint>(pts.size() / 2), pts.data(), 2, GLU_MAP1_TRIM_2);
      gluEndTrim(nurbs);
    }
    gluEndSurface(nurbs);
  }
};

void report(benchmark::State& state, std::size_t triangles, std::size_t patches) {
  state.counters["tri/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsRate);
  state.counters["tri/patch"] = static_cast<double>(triangles) / static_cast<double>(state.iterations() * patches);
}

// --- untrimmed: the 32 teapot patches at an n × n grid -------------------------------------------------
void BM_ours_untrimmed_teapot(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  ts::TriangleBuffers out;
  std::vector<ts::BernsteinTable> basis;
  std::size_t triangles = 0;
  for (auto _ : state) {
    for (const ts::Surface& s : teapot().surfaces) {
      ts::tessellate_untrimmed(s.patch, {n, n}, out, basis);
      triangles += out.triangle_count();
      benchmark::DoNotOptimize(out.positions.data());
    }
  }
  report(state, triangles, teapot().surfaces.size());
}

// The single-precision SIMD path (grid_row_kernel.hpp) that plan_surface picks where its error bound allows.
void BM_ours_untrimmed_teapot_float(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  ts::TriangleBuffers out;
  ts::FloatGridScratch scratch;
  std::size_t triangles = 0;
  for (auto _ : state) {
    for (const ts::Surface& s : teapot().surfaces) {
      ts::tessellate_untrimmed_float(s.patch, {n, n}, out, scratch);
      triangles += out.triangle_count();
      benchmark::DoNotOptimize(out.positions.data());
    }
  }
  report(state, triangles, teapot().surfaces.size());
}

void BM_glu_untrimmed_teapot(benchmark::State& state) {
  Glu glu;
  glu.domain_distance(static_cast<int>(state.range(0)));
  std::size_t triangles = 0;
  for (auto _ : state) triangles += glu.draw_all(teapot().surfaces);
  report(state, triangles, teapot().surfaces.size());
}

// --- trimmed: a bicubic patch with a circular hole at an n × n grid ---------------------------------------
void BM_ours_trimmed_hole(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const ts::PreparedSurface prepared = ts::prepare_surface(holed_patch());
  ts::SurfacePlan plan;
  plan.steps = {n, n};
  plan.epsilon = 1e-3;  // unused by polyline trims (degree 1: one segment each)
  plan.edge_length = 1.0;
  ts::TessellationSettings settings;
  plan.single_precision = ts::single_precision_allowed(prepared, plan.epsilon, settings);  // as plan_surface
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  std::size_t triangles = 0;
  for (auto _ : state) {
    triangles += ts::tessellate_trimmed(prepared, plan, settings, scratch, out).triangles;
    benchmark::DoNotOptimize(out.positions.data());
  }
  report(state, triangles, 1);
}

void BM_glu_trimmed_hole(benchmark::State& state) {
  Glu glu;
  glu.domain_distance(static_cast<int>(state.range(0)));
  std::size_t triangles = 0;
  for (auto _ : state) {
    glu.sink.positions.clear();
    glu.sink.normals.clear();
    glu.sink.triangles = 0;
    glu.draw(holed_patch());
    triangles += glu.sink.triangles;
  }
  report(state, triangles, 1);
}

// --- equal screen tolerance: triangle counts for the teapot seen by one camera ---------------------------
ts::Camera teapot_camera() {
  ts::Camera cam;
  cam.eye = {7, -9, 6};
  cam.target = {0.2, 0, 1.5};
  cam.width = 1280;
  cam.height = 720;
  return cam;
}

void BM_ours_teapot_at_pixel_tolerance(benchmark::State& state) {
  const ts::Camera cam = teapot_camera();
  const ts::Frustum frustum = ts::Frustum::of(cam);
  ts::TessellationSettings settings;
  settings.pixel_tolerance = static_cast<double>(state.range(0)) / 4.0;
  settings.max_edge_pixels = 1e9;  // deviation bound only, like GLU_PARAMETRIC_ERROR
  settings.back_face_culling = settings.frustum_culling = false;
  std::vector<ts::PreparedSurface> prepared;
  for (const ts::Surface& s : teapot().surfaces) prepared.push_back(ts::prepare_surface(s));
  ts::TessellationScratch scratch;
  ts::TriangleBuffers out;
  std::size_t triangles = 0;
  for (auto _ : state) {
    for (const ts::PreparedSurface& p : prepared)
      triangles += ts::tessellate_surface(p, cam, frustum, settings, scratch, out).triangles;
  }
  report(state, triangles, prepared.size());
  state.SetLabel("tolerance " + std::to_string(settings.pixel_tolerance) + " px");
}

void BM_glu_teapot_at_pixel_tolerance(benchmark::State& state) {
  Glu glu;
  const float tolerance = static_cast<float>(state.range(0)) / 4.0f;
  glu.screen_error(tolerance, teapot_camera());
  std::size_t triangles = 0;
  for (auto _ : state) triangles += glu.draw_all(teapot().surfaces);
  report(state, triangles, teapot().surfaces.size());
  state.SetLabel("tolerance " + std::to_string(tolerance) + " px");
}

}  // namespace

BENCHMARK(BM_ours_untrimmed_teapot)->Arg(4)->Arg(16)->Arg(64);
BENCHMARK(BM_ours_untrimmed_teapot_float)->Arg(4)->Arg(16)->Arg(64);
BENCHMARK(BM_glu_untrimmed_teapot)->Arg(4)->Arg(16)->Arg(64);
BENCHMARK(BM_ours_trimmed_hole)->Arg(8)->Arg(32)->Arg(128);
BENCHMARK(BM_glu_trimmed_hole)->Arg(8)->Arg(32)->Arg(128);
BENCHMARK(BM_ours_teapot_at_pixel_tolerance)->Arg(2)->Arg(4)->Arg(8);
BENCHMARK(BM_glu_teapot_at_pixel_tolerance)->Arg(2)->Arg(4)->Arg(8);

BENCHMARK_MAIN();
