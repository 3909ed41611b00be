// gpu_tessellation_benchmark.hpp — the GPU compute-shader tessellator (gpu_patch_tessellator.hpp) against the
// CPU's fastest path (the SIMD float row kernel, one core and every core) on the same untrimmed patches at the
// same uniform grids, with the GPU's output audited before anything is timed.
//
// Per grid size n (n × n steps on every patch):
//   1. Audit: one dispatch, then every patch of the first and the last copy read back and held by
//      grid_audit.hpp against the exact double evaluation (bound: gpu_float_error_bound), and against the CPU's
//      grid of the same patch (their distance within the sum of both float bounds; indices identical).
//   2. Rounds: every arm once per round, in a fresh random order (measure/round_order.hpp), each timed by the
//      harness's steady clock from the call to the last result being in memory (GPU: dispatch, then glFinish).
//      Arms: gpu; gpu-twin (the same dispatch again: an A/A pair the comparison must call equal); gpu-doubled
//      (two dispatches: a planted 2× slowdown it must find); cpu-1 (one core); cpu-all (every core, patches in
//      contiguous blocks, one std::thread each).
//   3. Comparisons: the main job's paired analysis (measure/paired_analysis.hpp: per-round log-ratios, a robust
//      estimate with its 95 % interval, verdicts against a ±2 % margin). The twin must come out equivalent and
//      the doubled arm slower, near 2×, for the run's comparisons to count.
// Outputs stay where their consumer reads them: GPU triangles in GPU buffers, CPU triangles in one
// TriangleBuffers per patch (capacity kept across rounds). Uploading the control points is not timed (scene
// data, uploaded once); reading triangles back is not timed (a renderer draws them where they are).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "measure/paired_comparison.hpp"
#include "render/gpu_patch_tessellator.hpp"
#include "tessellate/grid_audit.hpp"
#include "tessellate/grid_tessellator.hpp"
#include "tessellate/model.hpp"

namespace frontsteal::render {

struct GpuBenchmarkOptions {
  std::vector<int> steps = {8, 16, 32, 64};
  // Per grid size, each untrimmed patch of the scene is repeated until a batch holds about this many triangles
  // (at least two copies): enough to fill a large GPU, the same work for every arm.
  std::uint64_t target_triangles = 1'000'000;
  int rounds = 11;
  unsigned cpu_threads = 0;  // cpu-all's threads; 0: the hardware's
  std::uint64_t seed = 1;
  GpuPlantedDefect planted_defect = GpuPlantedDefect::none;  // tests: the audit must fail
  std::function<void(const std::string&)> progress;          // one line per step; may be empty
};

struct GpuArmTimes {
  std::string name;
  std::vector<double> seconds;  // one per round
  stats::Interval median_seconds;
  double triangles_per_second = 0;  // triangles / median seconds
};

struct GpuStepResult {
  int steps = 0;
  std::uint64_t copies = 0, patches = 0, triangles = 0, vertices = 0, output_bytes = 0;
  // Audit of the read-back GPU grids.
  std::uint64_t audited_patches = 0, failing_patches = 0, failing_vertices = 0, index_mismatches = 0;
  double max_position_error = 0, max_position_bound = 0, max_normal_angle = 0, max_gpu_cpu_distance = 0;
  std::uint64_t ill_conditioned_normals = 0;
  std::vector<GpuArmTimes> arms;                      // gpu, gpu-twin, gpu-doubled, cpu-1, cpu-all
  measure::PairedResult twin_vs_gpu;                  // A/A: must be equivalent
  measure::PairedResult doubled_vs_gpu;               // planted 2x: must be slower, near 2
  measure::PairedResult gpu_vs_cpu1, gpu_vs_cpu_all;  // ratio < 1: the GPU takes less time
  // The GPU's own clock (GL_TIME_ELAPSED around the gpu arm's dispatch, every round), beside the harness's.
  std::vector<double> gpu_clock_seconds;
  double gpu_clock_median_ms = 0;
  bool method_passed() const noexcept;
};

struct GpuBenchmarkResult {
  std::string renderer;  // vendor, renderer, OpenGL and EGL versions
  std::string cpu;
  unsigned cpu_threads = 0;
  std::uint64_t scene_patches = 0;  // untrimmed patches of the scene, before copies
  std::vector<GpuStepResult> steps;
  bool audit_passed() const noexcept;
};

// One read-back GPU grid against the exact surface (grid_audit.hpp, within gpu_float_error_bound) and against
// the CPU's grid of the same patch (made into `cpu_grid`: distance within both float bounds, identical indices).
struct GpuGridCheck {
  tess::GridAudit audit;
  double position_bound = 0, gpu_cpu_distance = 0;
  bool agrees_with_cpu = false;
  bool passed() const noexcept { return audit.passed() && agrees_with_cpu; }
};
GpuGridCheck check_gpu_grid(const tess::BezierPatch& patch, tess::StepSizes steps, const tess::TriangleBuffers& grid,
                            tess::TriangleBuffers& cpu_grid, tess::FloatGridScratch& scratch);

// The scene's untrimmed surfaces (trimmed ones are the CPU's: the GPU path has no trimming). Throws
// GraphicsError without OpenGL 4.3, std::invalid_argument when the scene has no untrimmed surface.
GpuBenchmarkResult run_gpu_tessellation_benchmark(const tess::Model& model, const GpuBenchmarkOptions& options);

}  // namespace frontsteal::render
