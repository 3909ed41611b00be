// components.hpp — surface adjacency and its connected components (paper §5.2: the triangles of a component
// are swapped in together, so the image never mixes old and new triangles along a shared edge).
//
// Two surfaces are adjacent when their boundaries share a point: each surface's boundary is sampled (the four
// patch edges when untrimmed, the trim loops mapped onto the surface when trimmed) and points closer than
// `tolerance` are matched through a hash grid of that cell size (a point is looked up in its cell and the 26
// around it). Components are the classes of a union–find over the matches. Surfaces touching at a single
// point join one component too: for rendering, that is the safe side.
#pragma once

#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/model.hpp"

namespace frontsteal::tess {

namespace detail {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

inline std::vector<glm::dvec3> boundary_samples(const Surface& s, int per_edge) {
  std::vector<glm::dvec3> out;
  if (s.loops.empty()) {
    for (int k = 0; k < per_edge; ++k) {
      const double t = static_cast<double>(k) / per_edge;
      for (const glm::dvec2 uv : {glm::dvec2{t, 0}, glm::dvec2{1, t}, glm::dvec2{1 - t, 1}, glm::dvec2{0, 1 - t}}) {
        out.push_back(evaluate(s.patch, uv.x, uv.y).position);
      }
    }
    return out;
  }
  for (const TrimLoop& loop : s.loops) {
    for (const glm::dvec2& uv : sample_loop(loop, per_edge)) out.push_back(evaluate(s.patch, uv.x, uv.y).position);
  }
  return out;
}

}  // namespace detail

// Sets every surface's `component` (0, 1, …, in order of first appearance) and returns the count.
inline int assign_components(Model& model, double tolerance, int samples_per_edge = 4) {
  const std::size_t n = model.surfaces.size();
  detail::UnionFind sets(n);
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept {
      return static_cast<std::size_t>(k.x * 73856093 ^ k.y * 19349663 ^ k.z * 83492791);
    }
  };
  std::unordered_map<Key, std::vector<std::pair<int, glm::dvec3>>, KeyHash> grid;
  for (std::size_t s = 0; s < n; ++s) {
    for (const glm::dvec3& p : detail::boundary_samples(model.surfaces[s], samples_per_edge)) {
      const Key k{static_cast<std::int64_t>(std::floor(p.x / tolerance)), static_cast<std::int64_t>(std::floor(p.y / tolerance)),
                  static_cast<std::int64_t>(std::floor(p.z / tolerance))};
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find({k.x + dx, k.y + dy, k.z + dz});
            if (it == grid.end()) continue;
            for (const auto& [other, q] : it->second) {
              if (other != static_cast<int>(s) && glm::length(p - q) <= tolerance) sets.unite(static_cast<int>(s), other);
            }
          }
        }
      }
      auto& bucket = grid[k];
      if (bucket.empty() || bucket.back().first != static_cast<int>(s)) bucket.emplace_back(static_cast<int>(s), p);
    }
  }
  std::vector<int> label(n, -1);
  int count = 0;
  for (std::size_t s = 0; s < n; ++s) {
    const int root = sets.find(static_cast<int>(s));
    if (label[root] < 0) label[root] = count++;
    model.surfaces[s].component = label[root];
  }
  return count;
}

}  // namespace frontsteal::tess
