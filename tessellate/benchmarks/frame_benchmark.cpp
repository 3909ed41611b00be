// frame_benchmark — single-thread full-frame tessellation of a generated plant (default 15,906 surfaces, the
// paper's largest model) along the deterministic camera path (camera_path.hpp): culling, view-dependent steps,
// trimming and triangulation of every surface into its own reused buffers, frame after frame.
// Counters: triangles per second, triangles and visible surfaces per frame; the benchmark's time is the frame
// time. One benchmark per path position (orbit, zoomed in), so both regimes are reported.
#include <benchmark/benchmark.h>

#include <vector>

#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;

namespace {

struct Scene {
  ts::Model model = ts::generate_plant({15906, 1});
  std::vector<ts::PreparedSurface> prepared;
  ts::Box box;
  Scene() {
    for (const ts::Surface& s : model.surfaces) prepared.push_back(ts::prepare_surface(s));
    box = ts::model_box(model);
  }
};

Scene& scene() {
  static Scene s;
  return s;
}

constexpr int kPathFrames = 16;

void BM_frame(benchmark::State& state) {
  Scene& sc = scene();
  const int first = static_cast<int>(state.range(0)), last = static_cast<int>(state.range(1));
  std::vector<ts::TriangleBuffers> buffers(sc.prepared.size());
  ts::TessellationScratch scratch;
  ts::TessellationSettings settings;
  std::size_t triangles = 0, visible = 0, frames = 0;
  int frame = first;
  for (auto _ : state) {
    const ts::Camera cam = ts::camera_on_path(sc.box, frame, kPathFrames);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    for (std::size_t k = 0; k < sc.prepared.size(); ++k) {
      const ts::SurfaceResult r = ts::tessellate_surface(sc.prepared[k], cam, frustum, settings, scratch, buffers[k]);
      triangles += r.triangles;
      visible += r.culled == ts::Culled::no;
    }
    ++frames;
    frame = frame == last ? first : frame + 1;
  }
  state.counters["tri/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsRate);
  state.counters["tri/frame"] = static_cast<double>(triangles) / static_cast<double>(frames);
  state.counters["visible/frame"] = static_cast<double>(visible) / static_cast<double>(frames);
}

}  // namespace

// Orbit frames 0–7, zoom frames 8–15.
BENCHMARK(BM_frame)
    ->Args({0, kPathFrames / 2 - 1})
    ->Name("frame_15906/orbit")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);
BENCHMARK(BM_frame)
    ->Args({kPathFrames / 2, kPathFrames - 1})
    ->Name("frame_15906/zoom")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);

BENCHMARK_MAIN();
