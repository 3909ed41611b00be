// bezier_patch.cpp — see bezier_patch.hpp.
#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess {

static_assert(kMaxDegree < 32, "evaluate() keys its cases by degree_u * 32 + degree_v");

namespace {
// Four doubles as one GCC vector: one AVX instruction per lane-wise operation in the AVX2 build below, two SSE2
// ones in the baseline build (where glm's scalar code left the compiler shuffling lanes).
typedef double Double4 __attribute__((vector_size(32)));

// The evaluator, built twice: for AVX2 and for the x86-64 baseline. Neither has FMA, and this file is compiled
// with -ffp-contract=off (tessellate/CMakeLists.txt), so both round every product and sum as the header's
// glm::dvec4 version does: the same bits on every CPU.
[[gnu::always_inline]] inline SurfacePoint evaluate_lanes(const BezierPatch& p, double u, double v) noexcept {
  switch (p.degree_u * 32 + p.degree_v) {  // degrees 1 to 3 unrolled (32 > kMaxDegree: one case per pair)
    case 32 + 1: return detail::evaluate_at<1, 1, Double4>(p, u, v);
    case 32 + 2: return detail::evaluate_at<1, 2, Double4>(p, u, v);
    case 32 + 3: return detail::evaluate_at<1, 3, Double4>(p, u, v);
    case 64 + 1: return detail::evaluate_at<2, 1, Double4>(p, u, v);
    case 64 + 2: return detail::evaluate_at<2, 2, Double4>(p, u, v);
    case 64 + 3: return detail::evaluate_at<2, 3, Double4>(p, u, v);
    case 96 + 1: return detail::evaluate_at<3, 1, Double4>(p, u, v);
    case 96 + 2: return detail::evaluate_at<3, 2, Double4>(p, u, v);
    case 96 + 3: return detail::evaluate_at<3, 3, Double4>(p, u, v);
    default: return detail::evaluate_at<0, 0, Double4>(p, u, v);
  }
}
__attribute__((target("avx2"))) SurfacePoint evaluate_avx2(const BezierPatch& p, double u, double v) noexcept {
  return evaluate_lanes(p, u, v);
}
SurfacePoint evaluate_baseline(const BezierPatch& p, double u, double v) noexcept { return evaluate_lanes(p, u, v); }
}  // namespace

SurfacePoint evaluate(const BezierPatch& p, double u, double v) noexcept {
  // Chosen once, by the features of the CPU it runs on (a plain branch rather than target_clones, whose
  // resolver symbols clang 14 names differently: the fuzz target builds this file with clang).
  static const bool avx2 = __builtin_cpu_supports("avx2");
  SurfacePoint sp = avx2 ? evaluate_avx2(p, u, v) : evaluate_baseline(p, u, v);
  if (sp.normal == glm::dvec3(0.0)) {
    // Collapsed edge: take the normal a hair towards the patch centre, where the surface is regular.
    const double nu = u + (0.5 - u) * 1e-6;
    const double nv = v + (0.5 - v) * 1e-6;
    sp.normal = detail::evaluate_at<0, 0>(p, nu, nv).normal;
  }
  return sp;
}

}  // namespace frontsteal::tess
