// frame_benchmark — single-thread full-frame tessellation of a generated plant (default 15,906 surfaces, the
// paper's largest model) along the deterministic camera path (camera_path.hpp): culling, view-dependent steps,
// trimming and triangulation of every surface into its own reused buffers, frame after frame.
// Counters: triangles per second, triangles and visible surfaces per frame; the benchmark's time is the frame
// time. One benchmark per path position (orbit, zoomed in), so both regimes are reported.
// The ".../phases" runs tessellate the same frames with a phase profile attached (phase_profile.hpp) and report
// each phase's milliseconds per frame as counters (cull_ms, plan_ms, ...; other_ms: the frame's time outside
// every phase, i.e. the loop itself); their frame time includes the profile's clock reads, so compare it with
// the plain run's to see what profiling costs.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
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

[[gnu::noinline]] void BM_frame(benchmark::State& state, bool profiled) {  // noinline: callgrind toggles on it
  Scene& sc = scene();
  const int first = static_cast<int>(state.range(0)), last = static_cast<int>(state.range(1));
  std::vector<ts::TriangleBuffers> buffers(sc.prepared.size());
  ts::TessellationScratch scratch;
  ts::PhaseProfile profile;
  if (profiled) scratch.profile = &profile;
  ts::TessellationSettings settings;
  std::size_t triangles = 0, visible = 0, frames = 0;
  int frame = first;
  double frame_seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const ts::Camera cam = ts::camera_on_path(sc.box, frame, kPathFrames);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    for (std::size_t k = 0; k < sc.prepared.size(); ++k) {
      const ts::SurfaceResult r = ts::tessellate_surface(sc.prepared[k], cam, frustum, settings, scratch, buffers[k]);
      triangles += r.triangles;
      visible += r.culled == ts::Culled::no;
    }
    ++frames;
    frame = frame == last ? first : frame + 1;
    frame_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["tri/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsRate);
  state.counters["tri/frame"] = static_cast<double>(triangles) / static_cast<double>(frames);
  state.counters["visible/frame"] = static_cast<double>(visible) / static_cast<double>(frames);
  if (profiled) {
    for (std::size_t p = 0; p < ts::kPhaseCount; ++p) {
      std::string name = ts::to_string(static_cast<ts::Phase>(p));
      std::replace(name.begin(), name.end(), ' ', '_');
      state.counters[name + "_ms"] = 1e3 * profile.seconds[p] / static_cast<double>(frames);
    }
    state.counters["other_ms"] = 1e3 * (frame_seconds - profile.total()) / static_cast<double>(frames);
  }
}

}  // namespace

// Orbit frames 0–7, zoom frames 8–15; plain, then with the phase profile.
BENCHMARK_CAPTURE(BM_frame, plain, false)
    ->Args({0, kPathFrames / 2 - 1})
    ->Name("frame_15906/orbit")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_frame, plain, false)
    ->Args({kPathFrames / 2, kPathFrames - 1})
    ->Name("frame_15906/zoom")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_frame, phases, true)
    ->Args({0, kPathFrames / 2 - 1})
    ->Name("frame_15906/orbit/phases")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);
BENCHMARK_CAPTURE(BM_frame, phases, true)
    ->Args({kPathFrames / 2, kPathFrames - 1})
    ->Name("frame_15906/zoom/phases")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(3.0);

// `frame_benchmark --frame-digest` prints a digest of all 16 frames' triangles instead (see frame_digest).
// The orbit's eight frames exactly once, for instruction counts that do not depend on the machine's speed:
//   valgrind --tool=callgrind --toggle-collect='*::BM_frame(*' frame_benchmark --benchmark_filter=orbit/8_frames
BENCHMARK_CAPTURE(BM_frame, plain, false)
    ->Args({0, kPathFrames / 2 - 1})
    ->Name("frame_15906/orbit/8_frames")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(kPathFrames / 2);

// FNV-1a over every frame's buffers (positions, normals, (u, v), indices), for "same bytes out" across changes.
std::uint64_t frame_digest() {
  Scene& sc = scene();
  std::vector<ts::TriangleBuffers> buffers(sc.prepared.size());
  ts::TessellationScratch scratch;
  std::uint64_t h = 0xcbf29ce484222325ull;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ p[k]) * 0x100000001b3ull;
  };
  for (int frame = 0; frame < kPathFrames; ++frame) {
    const ts::Camera cam = ts::camera_on_path(sc.box, frame, kPathFrames);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    for (std::size_t k = 0; k < sc.prepared.size(); ++k) {
      ts::TriangleBuffers& b = buffers[k];
      ts::tessellate_surface(sc.prepared[k], cam, frustum, {}, scratch, b);
      mix(b.positions.data(), b.positions.size() * sizeof(glm::vec3));
      mix(b.normals.data(), b.normals.size() * sizeof(glm::vec3));
      mix(b.uvs.data(), b.uvs.size() * sizeof(glm::vec2));
      mix(b.indices.data(), b.indices.size() * sizeof(std::uint32_t));
    }
  }
  return h;
}

int main(int argc, char** argv) {
  if (argc == 2 && std::string(argv[1]) == "--frame-digest") {
    std::printf("%016llx\n", static_cast<unsigned long long>(frame_digest()));
    return 0;
  }
  for (int k = 1; k < argc; ++k) {
    if (std::string(argv[k]) == "--help") {
      std::printf(
          "frame_benchmark: full frames of plant:15906 along the camera path, plain and with the phase profile.\n"
          "  --frame-digest   print a digest of all 16 frames' triangles (positions, normals, (u, v), indices) "
          "and exit\n\nGoogle Benchmark's options:\n");
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  scene();  // generated and prepared before any benchmark runs, so no benchmark's time or count includes it
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
