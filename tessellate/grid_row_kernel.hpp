// grid_row_kernel.hpp — one row of an untrimmed patch's grid in single precision, vectorized along the row.
//
// Why: the double-precision row evaluator (RowCurve, grid_tessellator.hpp) costs ~3(n+1) dvec4 multiply-adds
// per vertex, one vertex at a time. Here the row's collapsed control values are broadcast and the work runs
// across the row's vertices in SIMD lanes (structure of arrays: the v-basis table is stored as basis[k][j],
// outputs as x[j], y[j], … before they are interleaved), in float: 8 lanes with AVX2, 4 with SSE2. Position,
// both partials and the unit normal come out of the same pass. The kernel is built twice (AVX2+FMA and the
// x86-64 baseline) and picked once by the CPU's features (__builtin_cpu_supports).
//
// Precision: the caller uses it only when the float error bound (float_row_error_bound) is below a tenth of
// the surface's object-space tolerance; otherwise it keeps the double path. Vertices whose normal vanishes
// (a collapsed edge) are flagged so the caller computes that normal in double as before.
#pragma once

#include <cstdint>

#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess {

// Vertices per SIMD step; the basis tables and the scratch are padded to a multiple of it.
inline constexpr int kRowLanes = 8;
inline int padded_row(int count) noexcept { return (count + kRowLanes - 1) / kRowLanes * kRowLanes; }

// Structure-of-arrays view of a row's work. `basis`/`derivative`: (degree_v+1) rows of padded_row(count)
// floats, row k = B_k(v_j) / B_k'(v_j) for j = 0..count-1 (then padding). `value`/`du`: the row's collapsed homogeneous
// control values R_k and their u-derivatives, as (x, y, z, w). Outputs: `position` and `normal` interleaved (x, y, z
// per vertex), `degenerate[j]` = 1 where the normal vanished (0 otherwise).
struct RowKernelArgs {
  int degree_v = 0;
  int count = 0;
  const float* basis = nullptr;
  const float* derivative = nullptr;
  float value[kMaxDegree + 1][4];  // rows 0..degree_v set by the caller and read; the rest left unwritten
  float du[kMaxDegree + 1][4];
  float* position = nullptr;
  float* normal = nullptr;
  std::uint8_t* degenerate = nullptr;
  // Scratch: 6 arrays of padded_row(count) floats (positions and normals by coordinate), owned by the caller.
  float* scratch = nullptr;
};

void evaluate_row_float(const RowKernelArgs& args) noexcept;

// Which build of the kernel evaluate_row_float runs: the CPU's best (default), or the x86-64 baseline, so
// tests check both on a machine with AVX2.
enum class RowKernelBuild : std::uint8_t { best_for_cpu, baseline };
void set_row_kernel_build(RowKernelBuild build) noexcept;

// A bound on the absolute position error of evaluate_row_float for this patch: each homogeneous sum of
// degree_v+1 terms (basis in [0,1], summing to 1) errs by at most (degree_v+2)·u·max|R| with u = 2⁻²⁴,
// the division by w multiplies the relative error by about 2 and the value by max|P|·(w_max/w_min) … so
// (2·degree_v + 6)·u·max|P|·(w_max/w_min), with a factor 4 of margin.
double float_row_error_bound(const BezierPatch& patch) noexcept;

// What every float error bound of a patch scales with: max|P| over the control points' coordinates and the
// weights' spread w_max / w_min.
struct ControlNetScale {
  double max_coordinate = 0;
  double weight_spread = 1;
};
ControlNetScale control_net_scale(const BezierPatch& patch) noexcept;

}  // namespace frontsteal::tess
