#include "render/gpu_tessellation_benchmark.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>

#include "measure/machine_info.hpp"
#include "measure/round_order.hpp"
#include "tessellate/grid_audit.hpp"
#include "tessellate/grid_row_kernel.hpp"
#include "tessellate/grid_tessellator.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::render {

namespace {

using Clock = std::chrono::steady_clock;

// The CPU arm: patches [first, last) into their own buffers, each by the SIMD float row kernel.
void cpu_tessellate(const std::vector<const tess::BezierPatch*>& patches, tess::StepSizes steps, std::size_t first,
                    std::size_t last, std::vector<tess::TriangleBuffers>& out, tess::FloatGridScratch& scratch) {
  for (std::size_t k = first; k < last; ++k) tess::tessellate_untrimmed_float(*patches[k], steps, out[k], scratch);
}

void cpu_all(const std::vector<const tess::BezierPatch*>& patches, tess::StepSizes steps,
             std::vector<tess::TriangleBuffers>& out, std::vector<tess::FloatGridScratch>& scratch) {
  const std::size_t threads = scratch.size(), count = patches.size();
  std::vector<std::thread> team;
  team.reserve(threads);
  for (std::size_t t = 0; t < threads; ++t) {
    const std::size_t first = count * t / threads, last = count * (t + 1) / threads;
    team.emplace_back([&, t, first, last] { cpu_tessellate(patches, steps, first, last, out, scratch[t]); });
  }
  for (std::thread& th : team) th.join();
}

void audit_step(const std::vector<const tess::BezierPatch*>& patches, std::size_t scene_patches, tess::StepSizes steps,
                const GpuPatchTessellator& gpu, GpuStepResult& r) {
  tess::TriangleBuffers from_gpu, from_cpu;
  tess::FloatGridScratch scratch;
  // The first and the last copy: every distinct patch, at both ends of the GPU's buffers.
  std::vector<std::size_t> which;
  for (std::size_t k = 0; k < scene_patches; ++k) which.push_back(k);
  for (std::size_t k = patches.size() - scene_patches; k < patches.size() && k >= scene_patches; ++k)
    which.push_back(k);
  for (const std::size_t k : which) {
    const tess::BezierPatch& patch = *patches[k];
    gpu.read_back(k, from_gpu);
    const GpuGridCheck check = check_gpu_grid(patch, steps, from_gpu, from_cpu, scratch);
    const tess::GridAudit& a = check.audit;
    ++r.audited_patches;
    r.failing_patches += check.passed() ? 0 : 1;
    r.failing_vertices += a.failing_vertices;
    r.index_mismatches += a.index_mismatches + (a.shape_ok ? 0 : 1);
    r.ill_conditioned_normals += a.ill_conditioned_normals;
    r.max_position_error = std::max(r.max_position_error, a.max_position_error);
    r.max_position_bound = std::max(r.max_position_bound, check.position_bound);
    r.max_normal_angle = std::max(r.max_normal_angle, a.max_normal_angle);
    r.max_gpu_cpu_distance = std::max(r.max_gpu_cpu_distance, check.gpu_cpu_distance);
  }
}

measure::PairedResult compare(const std::vector<double>& candidate, const std::vector<double>& reference) {
  std::vector<measure::RoundPair> pairs;
  for (std::size_t k = 0; k < std::min(candidate.size(), reference.size()); ++k) {
    measure::RoundPair p;
    p.candidate = candidate[k];
    p.reference = reference[k];
    pairs.push_back(p);
  }
  measure::Settings settings;
  settings.adjust_for_probe = false;  // no CPU speed probe here: the GPU arms do not run on the CPU
  return measure::analyze_pairs(pairs, settings);
}

}  // namespace

bool GpuStepResult::method_passed() const noexcept {
  const double doubled = doubled_vs_gpu.chosen().ratio();
  return twin_vs_gpu.decision == measure::Decision::kEquivalent &&
         doubled_vs_gpu.decision == measure::Decision::kSlower && doubled > 1.8 && doubled < 2.2;
}

GpuGridCheck check_gpu_grid(const tess::BezierPatch& patch, tess::StepSizes steps, const tess::TriangleBuffers& grid,
                            tess::TriangleBuffers& cpu_grid, tess::FloatGridScratch& scratch) {
  GpuGridCheck c;
  c.position_bound = gpu_float_error_bound(patch);
  tess::GridAuditLimits limits;
  limits.position = c.position_bound;
  c.audit = tess::audit_grid(patch, steps, grid, limits);
  tess::tessellate_untrimmed_float(patch, steps, cpu_grid, scratch);
  c.gpu_cpu_distance = tess::max_position_difference(grid, cpu_grid);
  c.agrees_with_cpu =
      c.gpu_cpu_distance <= c.position_bound + tess::float_row_error_bound(patch) && grid.indices == cpu_grid.indices;
  return c;
}

bool GpuBenchmarkResult::audit_passed() const noexcept {
  return std::all_of(steps.begin(), steps.end(), [](const GpuStepResult& s) { return s.failing_patches == 0; });
}

GpuBenchmarkResult run_gpu_tessellation_benchmark(const tess::Model& model, const GpuBenchmarkOptions& options) {
  GpuBenchmarkResult result;
  std::vector<const tess::BezierPatch*> scene;
  for (const tess::Surface& s : model.surfaces) {
    if (!tess::prepare_surface(s).trimmed()) scene.push_back(&s.patch);
  }
  if (scene.empty()) throw std::invalid_argument("the scene has no untrimmed surface (the GPU path does not trim)");
  if (options.rounds < 3) throw std::invalid_argument("rounds must be at least 3");
  result.scene_patches = scene.size();
  result.cpu = frontsteal::cpu_model();
  result.cpu_threads = options.cpu_threads > 0 ? options.cpu_threads : frontsteal::hardware_cores();

  GpuPatchTessellator gpu(options.planted_defect);
  std::vector<tess::FloatGridScratch> scratch(result.cpu_threads);
  const std::vector<std::string> names = {"gpu", "gpu-twin", "gpu-doubled", "cpu-1", "cpu-all"};
  for (const int n : options.steps) {
    if (n < 1 || n > 4096) throw std::invalid_argument("steps must be within 1..4096, got " + std::to_string(n));
    const tess::StepSizes steps{n, n};
    GpuStepResult r;
    r.steps = n;
    const std::uint64_t per_copy = 2ull * static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n) * scene.size();
    r.copies = std::max<std::uint64_t>(2, (options.target_triangles + per_copy / 2) / per_copy);
    std::vector<const tess::BezierPatch*> patches;
    for (std::uint64_t c = 0; c < r.copies; ++c) patches.insert(patches.end(), scene.begin(), scene.end());
    std::vector<tess::TriangleBuffers> cpu_out(patches.size());
    gpu.load(patches, std::vector<tess::StepSizes>(patches.size(), steps));
    r.patches = gpu.patches();
    r.triangles = gpu.triangles();
    r.vertices = gpu.vertices();
    r.output_bytes = gpu.output_bytes();
    gpu.timed_dispatch(1);
    audit_step(patches, scene.size(), steps, gpu, r);
    cpu_tessellate(patches, steps, 0, patches.size(), cpu_out, scratch[0]);  // warm: buffers at full capacity

    r.arms.resize(names.size());
    for (std::size_t a = 0; a < names.size(); ++a) r.arms[a].name = names[a];
    for (int round = 0; round < options.rounds; ++round) {
      for (const std::size_t a : measure::round_order(names.size(), options.seed + static_cast<std::uint64_t>(n),
                                                      static_cast<std::size_t>(round), measure::OrderKind::kRandom)) {
        const Clock::time_point start = Clock::now();
        switch (a) {
          case 0: r.gpu_clock_seconds.push_back(gpu.timed_dispatch(1)); break;
          case 1: gpu.timed_dispatch(1); break;
          case 2: gpu.timed_dispatch(2); break;
          case 3: cpu_tessellate(patches, steps, 0, patches.size(), cpu_out, scratch[0]); break;
          default: cpu_all(patches, steps, cpu_out, scratch); break;
        }
        r.arms[a].seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      }
    }
    for (GpuArmTimes& arm : r.arms) {
      arm.median_seconds = stats::bootstrap_median_ci(arm.seconds);
      arm.triangles_per_second = static_cast<double>(r.triangles) / arm.median_seconds.median;
    }
    r.gpu_clock_median_ms = 1e3 * frontsteal::median(r.gpu_clock_seconds);
    r.twin_vs_gpu = compare(r.arms[1].seconds, r.arms[0].seconds);
    r.doubled_vs_gpu = compare(r.arms[2].seconds, r.arms[0].seconds);
    r.gpu_vs_cpu1 = compare(r.arms[0].seconds, r.arms[3].seconds);
    r.gpu_vs_cpu_all = compare(r.arms[0].seconds, r.arms[4].seconds);
    if (options.progress) {
      char line[256];
      std::snprintf(line, sizeof line,
                    "%d x %d steps: %llu triangles; audit %s; gpu %.3g tri/s, cpu-1 %.3g, cpu-all %.3g", n, n,
                    static_cast<unsigned long long>(r.triangles), r.failing_patches == 0 ? "passed" : "FAILED",
                    r.arms[0].triangles_per_second, r.arms[3].triangles_per_second, r.arms[4].triangles_per_second);
      options.progress(line);
    }
    result.steps.push_back(std::move(r));
    gpu.load({}, {});  // frees the GPU's buffers before the next size
  }
  return result;
}

}  // namespace frontsteal::render
