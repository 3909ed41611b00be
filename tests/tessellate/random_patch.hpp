// Fixed-seed random Bézier patches for the tessellation property tests.
#pragma once

#include <random>

#include "tessellate/bezier_patch.hpp"

namespace frontsteal::tess::testing {

// Control points uniform in [-1,1]³; weights uniform in [0.5, 2] when rational, else 1.
inline BezierPatch random_patch(std::mt19937_64& rng, int du, int dv, bool rational) {
  std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(0.5, 2.0);
  BezierPatch p(du, dv);
  for (int i = 0; i <= du; ++i) {
    for (int j = 0; j <= dv; ++j) p.set(i, j, {coord(rng), coord(rng), coord(rng)}, rational ? weight(rng) : 1.0);
  }
  return p;
}

}  // namespace frontsteal::tess::testing
