// The GPU compute-shader tessellator (render/gpu_patch_tessellator.hpp), on whatever OpenGL 4.3 the machine has
// (Mesa's llvmpipe where there is no GPU): its grids pass grid_audit.hpp against the exact evaluation and match
// the CPU's grids, and both planted shader defects make the audit fail. grid_audit.hpp itself is checked
// against the CPU's double grid (passes) and a hand-broken copy (fails).
#include <catch2/catch.hpp>

#include <random>
#include <utility>

#include "render/gpu_patch_tessellator.hpp"
#include "render/gpu_tessellation_benchmark.hpp"
#include "render/headless_gl.hpp"
#include "tessellate/grid_audit.hpp"
#include "tessellate/grid_row_kernel.hpp"
#include "tessellate/model_format.hpp"
#include "tessellate/scene_generator.hpp"
#include "tests/tessellate/random_patch.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

ts::Model teapot() { return ts::load_scene("teapot", FRONTSTEAL_DATA_DIR); }

std::vector<const ts::BezierPatch*> patches_of(const ts::Model& m) {
  std::vector<const ts::BezierPatch*> out;
  for (const ts::Surface& s : m.surfaces) out.push_back(&s.patch);
  return out;
}

// Loads the patches at `steps` (a non-square grid, so a swap of u and v cannot pass by symmetry), runs the
// shader once and audits every patch; returns how many fail.
int failing_patches(const std::vector<const ts::BezierPatch*>& patches, rd::GpuPlantedDefect defect,
                    ts::StepSizes steps) {
  rd::GpuPatchTessellator gpu(defect);
  gpu.load(patches, std::vector<ts::StepSizes>(patches.size(), steps));
  gpu.dispatch();
  rd::GpuPatchTessellator::finish();
  int failing = 0;
  ts::TriangleBuffers grid, cpu;
  ts::FloatGridScratch scratch;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    gpu.read_back(k, grid);
    failing += rd::check_gpu_grid(*patches[k], steps, grid, cpu, scratch).passed() ? 0 : 1;
  }
  return failing;
}

// The same for every teapot patch.
int failing_patches(rd::GpuPlantedDefect defect, ts::StepSizes steps) {
  const ts::Model m = teapot();
  return failing_patches(patches_of(m), defect, steps);
}

}  // namespace

TEST_CASE("grid_audit passes the CPU's double grid and fails a moved vertex and a swapped index", "[render][gpu]") {
  const ts::Model m = teapot();
  const ts::BezierPatch& patch = m.surfaces.at(0).patch;
  const ts::StepSizes steps{6, 9};
  ts::TriangleBuffers grid;
  std::vector<ts::BernsteinTable> scratch;
  ts::tessellate_untrimmed(patch, steps, grid, scratch);
  ts::GridAuditLimits limits;
  limits.position = 1e-6;
  CHECK(ts::audit_grid(patch, steps, grid, limits).passed());

  ts::TriangleBuffers moved = grid;
  moved.positions[17].y += 1e-4f;
  const ts::GridAudit a = ts::audit_grid(patch, steps, moved, limits);
  CHECK_FALSE(a.passed());
  CHECK(a.failing_vertices == 1);

  ts::TriangleBuffers swapped = grid;
  std::swap(swapped.indices[4], swapped.indices[5]);
  CHECK(ts::audit_grid(patch, steps, swapped, limits).index_mismatches == 2);

  ts::TriangleBuffers short_grid = grid;
  short_grid.uvs.pop_back();
  CHECK_FALSE(ts::audit_grid(patch, steps, short_grid, limits).shape_ok);
}

TEST_CASE("GPU tessellation: the compute shader's grids pass the audit, planted shader defects do not",
          "[render][gpu]") {
  rd::HeadlessGL gl(16, 16, {4, 3});
  gl.make_current();
  CHECK(failing_patches(rd::GpuPlantedDefect::none, {7, 12}) == 0);
  CHECK(failing_patches(rd::GpuPlantedDefect::none, {1, 1}) == 0);
  CHECK(failing_patches(rd::GpuPlantedDefect::swapped_parameters, {7, 12}) > 0);
  CHECK(failing_patches(rd::GpuPlantedDefect::last_row_unwritten, {7, 12}) == 32);
  gl.release();
}

TEST_CASE("GPU tessellation benchmark: audit, rounds and the method's check on a small run", "[render][gpu]") {
  rd::HeadlessGL gl(16, 16, {4, 3});
  gl.make_current();
  rd::GpuBenchmarkOptions o;
  o.steps = {4, 8};
  o.target_triangles = 1;  // the least: two copies of every patch
  o.rounds = 5;
  o.cpu_threads = 2;
  const rd::GpuBenchmarkResult r = rd::run_gpu_tessellation_benchmark(teapot(), o);
  REQUIRE(r.steps.size() == 2);
  CHECK(r.audit_passed());
  CHECK(r.scene_patches == 32);
  for (const rd::GpuStepResult& s : r.steps) {
    CHECK(s.copies == 2);
    CHECK(s.patches == 64);
    CHECK(s.triangles == 64u * 2u * static_cast<unsigned>(s.steps * s.steps));
    CHECK(s.audited_patches == 64);
    REQUIRE(s.arms.size() == 5);
    for (const rd::GpuArmTimes& a : s.arms) CHECK(a.seconds.size() == 5);
  }
  o.planted_defect = rd::GpuPlantedDefect::swapped_parameters;
  o.steps = {6};
  CHECK_FALSE(rd::run_gpu_tessellation_benchmark(teapot(), o).audit_passed());
  gl.release();
}

TEST_CASE("GPU tessellation: degrees above 7 (imported CAD faces) get a program of their own and pass the audit",
          "[render][gpu]") {
  rd::HeadlessGL gl(16, 16, {4, 3});
  gl.make_current();
  std::mt19937_64 rng(11);
  std::vector<ts::BezierPatch> owned;
  for (const auto [du, dv] : {std::pair{2, 11}, std::pair{8, 8}, std::pair{3, 3}, std::pair{ts::kMaxDegree, 2},
                              std::pair{ts::kMaxDegree, ts::kMaxDegree}}) {
    owned.push_back(frontsteal::tess::testing::random_patch(rng, du, dv, true));
  }
  std::vector<const ts::BezierPatch*> patches;
  for (const ts::BezierPatch& p : owned) patches.push_back(&p);
  CHECK(failing_patches(patches, rd::GpuPlantedDefect::none, {5, 9}) == 0);
  CHECK(failing_patches(patches, rd::GpuPlantedDefect::swapped_parameters, {5, 9}) == static_cast<int>(patches.size()));
  gl.release();
}

// (A context without compute shaders cannot be made here: Mesa answers a 3.3 core request with its 4.5.)
TEST_CASE("GPU tessellation refuses a scene with nothing untrimmed", "[render][gpu]") {
  rd::HeadlessGL gl(16, 16, {4, 3});
  gl.make_current();
  CHECK_THROWS_AS(rd::run_gpu_tessellation_benchmark(ts::Model{}, {}), std::invalid_argument);
  CHECK(rd::gpu_planted_defect_named("swapped-parameters") == rd::GpuPlantedDefect::swapped_parameters);
  CHECK_FALSE(rd::gpu_planted_defect_named("nonsense").has_value());
  gl.release();
}
