// piece_triangulation_benchmark — ear clipping against the constrained triangulation on one piece of
// n ring vertices, the choice the trimmed path makes by size (kConstrainedTriangulationMinVertices). The piece
// is what a coarse grid on a densely trimmed face gives: a smooth trim polyline densely sampled, here a wavy
// closed curve (radius 0.4 + 0.05·sin 7θ about the cell's centre) with a circular hole of n/4 vertices.
//   ./build/release/tessellate/benchmarks/piece_triangulation_benchmark --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "tessellate/constrained_triangulation.hpp"
#include "tessellate/polygon_triangulation.hpp"

namespace ts = frontsteal::tess;

namespace {

struct Piece {
  ts::PolygonRing outer;
  std::vector<ts::PolygonRing> holes;
};

Piece wavy_with_hole(int n) {
  Piece piece;
  std::uint32_t id = 0;
  const int outer_n = n - n / 4, hole_n = n / 4;
  for (int k = 0; k < outer_n; ++k) {
    const double a = 2 * std::numbers::pi * k / outer_n, r = 0.4 + 0.05 * std::sin(7 * a);
    piece.outer.push_back({glm::dvec2(0.5 + r * std::cos(a), 0.5 + r * std::sin(a)), id++});
  }
  piece.holes.emplace_back();
  for (int k = 0; k < hole_n; ++k) {
    const double a = -2 * std::numbers::pi * k / hole_n;
    piece.holes.back().push_back({glm::dvec2(0.5 + 0.2 * std::cos(a), 0.5 + 0.2 * std::sin(a)), id++});
  }
  return piece;
}

void ear_clipping(benchmark::State& state) {
  const Piece piece = wavy_with_hole(static_cast<int>(state.range(0)));
  ts::PolygonRing ring;
  std::vector<ts::PolygonRing> holes;
  std::vector<std::uint32_t> triangles, next, prev;
  for (auto _ : state) {
    ring = piece.outer;
    holes = piece.holes;
    triangles.clear();
    ts::join_holes(ring, holes);
    ts::clip_ears(ring, triangles, next, prev);
    benchmark::DoNotOptimize(triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles.size() / 3);
}

void constrained_triangulation(benchmark::State& state) {
  const Piece piece = wavy_with_hole(static_cast<int>(state.range(0)));
  std::vector<std::uint32_t> triangles;
  for (auto _ : state) {
    triangles.clear();
    if (!ts::triangulate_constrained(piece.outer, piece.holes, triangles)) state.SkipWithError("refused");
    benchmark::DoNotOptimize(triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles.size() / 3);
}

}  // namespace

BENCHMARK(ear_clipping)->RangeMultiplier(2)->Range(16, 4096)->Arg(96)->Unit(benchmark::kMicrosecond);
BENCHMARK(constrained_triangulation)->RangeMultiplier(2)->Range(16, 4096)->Arg(96)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
