// gpu_patch_tessellator.hpp — untrimmed rational Bézier patches tessellated on the GPU by an OpenGL 4.3 compute
// shader, through the same EGL context the renderer uses (headless_gl.hpp; no CUDA-only path, so it runs on any
// vendor's driver and on Mesa's llvmpipe).
//
// The output is the CPU's grid (grid_tessellator.hpp), patch by patch, in four shader storage buffers laid out
// like TriangleBuffers: positions and normals (3 floats per vertex), (u, v) (2 floats), indices (3 per triangle,
// patch-local, the order of grid_indices). One work group per patch: its invocations load the patch's
// homogeneous control points into shared memory once, then each evaluates whole vertices — Bernstein values by
// the same recurrence as bezier_patch.hpp, the full tensor sum, the quotient rule for S_u and S_v, the normal
// S_u × S_v — and writes the two triangles of the cells it owns. Everything is float; the error bound below
// says how far that may stray, and grid_audit.hpp holds read-back grids to it against the exact evaluation.
//
// The triangles stay in GPU memory (where a renderer draws them from); read_back() copies one patch's grid to
// the CPU for the audit. The context must be current on the calling thread for every call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/grid_tessellator.hpp"
#include "tessellate/step_sizes.hpp"

namespace frontsteal::render {

// Negative controls only: defects planted in the shader so tests can show the audit catches them.
// `swapped_parameters` evaluates S(v, u) instead of S(u, v); `last_row_unwritten` leaves the u = 1 row of every
// patch as the buffer held it.
enum class GpuPlantedDefect : std::uint8_t { none, swapped_parameters, last_row_unwritten };
std::optional<GpuPlantedDefect> gpu_planted_defect_named(std::string_view name);

// A bound on the distance between the shader's float vertex and the exact point: each Bernstein value errs by
// about degree·u (u = 2⁻²⁴), the tensor sum of (m+1)(n+1) non-negative weights summing to 1 by (m+n+2)·u relative
// to max|H|, the control points' rounding to float adds u, and the division by w about 2u relative, times the
// weights' spread — (2(m+n)+6)·u·max|P|·(w_max/w_min), with a factor 4 of margin (fused multiply-adds and the
// drivers' division, which GLSL lets be a few ulp off).
double gpu_float_error_bound(const tess::BezierPatch& patch) noexcept;

class GpuPatchTessellator {
 public:
  // Compiles the shader; throws GraphicsError (headless_gl.hpp) when the context lacks OpenGL 4.3 compute
  // shaders or the shader does not compile.
  explicit GpuPatchTessellator(GpuPlantedDefect defect = GpuPlantedDefect::none);
  ~GpuPatchTessellator();
  GpuPatchTessellator(const GpuPatchTessellator&) = delete;
  GpuPatchTessellator& operator=(const GpuPatchTessellator&) = delete;

  // Uploads the patches (as float homogeneous control points) and their grids, and sizes the output buffers.
  // Throws std::invalid_argument for mismatched sizes or steps < 1, GraphicsError when an output buffer would
  // exceed what the driver allows in one shader storage block (the message gives both sizes).
  void load(const std::vector<const tess::BezierPatch*>& patches, const std::vector<tess::StepSizes>& steps);

  // Records the dispatches that tessellate every loaded patch; returns without waiting for the GPU.
  void dispatch();
  // Waits until the GPU has finished all work submitted so far (glFinish).
  static void finish();
  // `times` dispatch()es, then finish(); returns the GPU's own time for them in seconds (a GL_TIME_ELAPSED
  // query): the device's clock, reported beside the harness's wall clock, never instead of it.
  double timed_dispatch(int times = 1);

  std::size_t patches() const noexcept { return steps_.size(); }
  std::uint64_t vertices() const noexcept { return total_vertices_; }
  std::uint64_t triangles() const noexcept { return total_indices_ / 3; }
  std::uint64_t output_bytes() const noexcept;  // positions, normals, (u, v) and indices

  // Patch k's grid, copied from the GPU into `out` (sized like the CPU's buffers).
  void read_back(std::size_t k, tess::TriangleBuffers& out) const;

 private:
  // Degrees up to 7 each way (bicubic and most CAD) share one program; higher degrees up to tess::kMaxDegree
  // compile one sized for them when loaded.
  static constexpr int kCommonOrder = 8;
  void use_order(int order);

  GpuPlantedDefect defect_ = GpuPlantedDefect::none;
  int order_ = 0;
  unsigned program_ = 0;
  unsigned buffers_[6] = {};  // headers, controls, positions, normals, uvs, indices
  int patch_base_location_ = -1;
  int max_groups_ = 65535;
  std::vector<tess::StepSizes> steps_;
  std::vector<std::uint64_t> first_vertex_, first_index_;
  std::uint64_t total_vertices_ = 0, total_indices_ = 0;
};

}  // namespace frontsteal::render
