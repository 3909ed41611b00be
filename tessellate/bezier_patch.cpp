// bezier_patch.cpp — see bezier_patch.hpp.
#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess {

static_assert(kMaxDegree < 32, "evaluate() keys its cases by degree_u * 32 + degree_v");

namespace {
// Four doubles as one GCC vector: one AVX instruction per lane-wise operation in the AVX2 clone, two SSE2 ones
// in the default clone (where glm's scalar code left the compiler shuffling lanes).
typedef double Double4 __attribute__((vector_size(32)));
}  // namespace

// Cloned for AVX2 (picked at load time by the CPU's features): the homogeneous sums then take one instruction
// each. AVX2 without FMA, and the build does not contract a·b + c (ISO C++ mode), so both clones round every
// operation as the header's glm::dvec4 version does: the same bits on every CPU.
__attribute__((target_clones("avx2", "default"))) SurfacePoint evaluate(const BezierPatch& p, double u,
                                                                        double v) noexcept {
  SurfacePoint sp;
  switch (p.degree_u * 32 + p.degree_v) {  // degrees 1 to 3 unrolled (32 > kMaxDegree: one case per pair)
    case 32 + 1: sp = detail::evaluate_at<1, 1, Double4>(p, u, v); break;
    case 32 + 2: sp = detail::evaluate_at<1, 2, Double4>(p, u, v); break;
    case 32 + 3: sp = detail::evaluate_at<1, 3, Double4>(p, u, v); break;
    case 64 + 1: sp = detail::evaluate_at<2, 1, Double4>(p, u, v); break;
    case 64 + 2: sp = detail::evaluate_at<2, 2, Double4>(p, u, v); break;
    case 64 + 3: sp = detail::evaluate_at<2, 3, Double4>(p, u, v); break;
    case 96 + 1: sp = detail::evaluate_at<3, 1, Double4>(p, u, v); break;
    case 96 + 2: sp = detail::evaluate_at<3, 2, Double4>(p, u, v); break;
    case 96 + 3: sp = detail::evaluate_at<3, 3, Double4>(p, u, v); break;
    default: sp = detail::evaluate_at<0, 0, Double4>(p, u, v); break;
  }
  if (sp.normal == glm::dvec3(0.0)) {
    // Collapsed edge: take the normal a hair towards the patch centre, where the surface is regular.
    const double nu = u + (0.5 - u) * 1e-6;
    const double nv = v + (0.5 - v) * 1e-6;
    sp.normal = detail::evaluate_at<0, 0>(p, nu, nv).normal;
  }
  return sp;
}

}  // namespace frontsteal::tess
