// grid_row_kernel.cpp — see grid_row_kernel.hpp.
#include "tessellate/grid_row_kernel.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace frontsteal::tess {

namespace {

// W lanes as a GCC vector type: 8 (one AVX register) in the AVX2+FMA build of the kernel, 4 (one SSE register)
// in the baseline build; narrower there because twelve 8-lane accumulators would not fit 16 SSE registers.
// Written out rather than left to the auto-vectorizer, which gave up on the unrolled degree loop.
// (Two concrete typedefs: GCC drops vector attributes on alias templates.)
typedef float Lanes8 __attribute__((vector_size(32)));
typedef float Lanes4 __attribute__((vector_size(16)));
template <int W>
struct LaneType;
template <>
struct LaneType<8> {
  using type = Lanes8;
};
template <>
struct LaneType<4> {
  using type = Lanes4;
};
template <int W>
using Lanes = typename LaneType<W>::type;

template <int W>
[[gnu::always_inline]] inline Lanes<W> load(const float* p) noexcept {
  Lanes<W> v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
template <int W>
[[gnu::always_inline]] inline void store(float* p, Lanes<W> v) noexcept {
  __builtin_memcpy(p, &v, sizeof v);
}

// The row for one degree: k = 0..D unrolled, W vertices per step (D = 0: the degree read at run time, for the
// rare degrees above 7 imported CAD faces may have). The basis tables and the scratch are padded
// to a multiple of kRowLanes (a multiple of W); padding lanes compute garbage that is never stored.
template <int D, int W>
[[gnu::always_inline]] inline void row(const RowKernelArgs& a) noexcept {
  using V = Lanes<W>;
  const int n = a.count, padded = padded_row(n);
  float* sx = a.scratch;
  float* sy = sx + padded;
  float* sz = sy + padded;
  float* nx = sz + padded;
  float* ny = nx + padded;
  float* nz = ny + padded;
  const int degree = D > 0 ? D : a.degree_v;
  for (int j = 0; j < padded; j += W) {
    V s0{}, s1{}, s2{}, s3{}, u0{}, u1{}, u2{}, u3{}, v0{}, v1{}, v2{}, v3{};
#pragma GCC unroll 8
    for (int k = 0; k <= degree; ++k) {
      const V bk = load<W>(a.basis + k * padded + j), dk = load<W>(a.derivative + k * padded + j);
      s0 += bk * a.value[k][0], s1 += bk * a.value[k][1], s2 += bk * a.value[k][2], s3 += bk * a.value[k][3];
      u0 += bk * a.du[k][0], u1 += bk * a.du[k][1], u2 += bk * a.du[k][2], u3 += bk * a.du[k][3];
      v0 += dk * a.value[k][0], v1 += dk * a.value[k][1], v2 += dk * a.value[k][2], v3 += dk * a.value[k][3];
    }
    const V inv_w = 1.0f / s3;
    const V px = s0 * inv_w, py = s1 * inv_w, pz = s2 * inv_w;
    // Quotient rule: S_u = (H_u.xyz − P·H_u.w) / w, the same for v.
    const V ax = (u0 - px * u3) * inv_w, ay = (u1 - py * u3) * inv_w, az = (u2 - pz * u3) * inv_w;
    const V bx = (v0 - px * v3) * inv_w, by = (v1 - py * v3) * inv_w, bz = (v2 - pz * v3) * inv_w;
    const V cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
    const V len2 = cx * cx + cy * cy + cz * cz;
    V len;
#pragma GCC unroll 8
    for (int l = 0; l < W; ++l) len[l] = __builtin_sqrtf(len2[l]);  // becomes one sqrtps
    const V safe = len > 0.0f ? len : V{} + 1.0f;  // a vanished normal stays zero (and is flagged below)
    store<W>(sx + j, px), store<W>(sy + j, py), store<W>(sz + j, pz);
    store<W>(nx + j, cx / safe), store<W>(ny + j, cy / safe), store<W>(nz + j, cz / safe);
  }
  for (int j = 0; j < n; ++j) {
    a.position[3 * j] = sx[j], a.position[3 * j + 1] = sy[j], a.position[3 * j + 2] = sz[j];
    a.normal[3 * j] = nx[j], a.normal[3 * j + 1] = ny[j], a.normal[3 * j + 2] = nz[j];
    a.degenerate[j] = nx[j] == 0.0f && ny[j] == 0.0f && nz[j] == 0.0f;
  }
}

template <int W>
[[gnu::always_inline]] inline void dispatch_degree(const RowKernelArgs& a) noexcept {
  switch (a.degree_v) {
    case 1: row<1, W>(a); break;
    case 2: row<2, W>(a); break;
    case 3: row<3, W>(a); break;
    case 4: row<4, W>(a); break;
    case 5: row<5, W>(a); break;
    case 6: row<6, W>(a); break;
    case 7: row<7, W>(a); break;
    default: row<0, W>(a); break;
  }
}

__attribute__((target("avx2,fma"))) void row_avx2(const RowKernelArgs& a) noexcept { dispatch_degree<8>(a); }
void row_baseline(const RowKernelArgs& a) noexcept { dispatch_degree<4>(a); }

}  // namespace

namespace {
std::atomic<bool> g_force_baseline{false};  // set_row_kernel_build (tests)
}  // namespace

void evaluate_row_float(const RowKernelArgs& a) noexcept {
  // Chosen once, by the features of the CPU it runs on (not by its model name).
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (avx2 && !g_force_baseline.load(std::memory_order_relaxed)) {
    row_avx2(a);
  } else {
    row_baseline(a);
  }
}

void set_row_kernel_build(RowKernelBuild build) noexcept {
  g_force_baseline.store(build == RowKernelBuild::baseline, std::memory_order_relaxed);
}

ControlNetScale control_net_scale(const BezierPatch& patch) noexcept {
  double max_p = 0, w_min = INFINITY, w_max = 0;
  for (const glm::dvec4& h : patch.control) {
    const glm::dvec3 p = glm::dvec3(h) / h.w;
    max_p = std::max({max_p, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    w_min = std::min(w_min, h.w);
    w_max = std::max(w_max, h.w);
  }
  return {max_p, w_max / w_min};
}

double float_row_error_bound(const BezierPatch& patch) noexcept {
  const ControlNetScale net = control_net_scale(patch);
  constexpr double kUnit = 1.0 / 16777216.0;  // 2^-24
  return 4.0 * (2.0 * patch.degree_v + 6.0) * kUnit * net.max_coordinate * net.weight_spread;
}

}  // namespace frontsteal::tess
