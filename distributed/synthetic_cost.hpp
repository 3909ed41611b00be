// synthetic_cost.hpp — the synthetic workloads' cost shapes, shared by frontsteal-mpi (synthetic:N, cascade:N)
// and the distributed simulator, so that a measured and a SIMULATED run price every item the same way.
//
//   skewed   (synthetic:N) a fifth of the ids are `skew` times heavier, and that window moves with the frame so
//            last frame's allocation is never quite right. Round robin over ranks spreads the window evenly, so
//            static round robin already serves it (0.98-1.00 of ideal): it shows the protocol, not its need.
//   cascade  (cascade:N) the ids stand for space (screen or object regions in spatial order, as a cluster
//            renderer assigns them), and the cost concentrates the way a zoom concentrates refinement: a
//            binomial multiplicative cascade, a random binary tree over the ids in which every node sends a
//            fraction p of its cost to one child and 1 - p to the other (de Wijs's binomial cascade; Mandelbrot,
//            "Intermittent turbulence in self-similar cascades", J. Fluid Mech. 62, 1974). The side is a
//            fixed-seed coin per node; p = 0.8 + 0.1 sin(phase + 0.3 frame) on the top kFocusLevels levels (the
//            zoom's target), 0.65 + 0.1 sin(...) down to kMovingLevels (the camera moves: the hot spots stay and
//            change intensity from frame to frame), 0.5 +- 0.025 below (fine-grained noise). Mean cost 1 per
//            item. Static assignment by space (contiguous blocks, the `static-space` scheduler) gets about a third
//            of ideal at 4 ranks and a tenth at 256; round robin balances it at 4 ranks (every hot spot is many
//            items wide) and gets about 0.9 at 256 with 200,000 items; no item exceeds a fifth of a rank's ideal
//            share at 256, so ideal is reachable (tests/distributed/mpi_workload_test.cpp holds these).
//            What it is not: UTS (Olivier et al., LCPC 2006) discovers its tree while it runs; here a frame's
//            costs are fixed before the frame starts, but no scheduler is told them.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::mpi {

inline bool synthetic_heavy(int frame, ItemId id, ItemId n) noexcept {
  const std::uint64_t shifted = (std::uint64_t{id} + std::uint64_t(frame) * (n / 37 + 1)) % n;
  return shifted * 5 >= std::uint64_t{n} * 4;
}

enum class CostShape : std::uint8_t { kSkewed, kCascade };

// "synthetic:N" -> (kSkewed, N), "cascade:N" -> (kCascade, N); anything else: nullopt-like {false}.
struct SyntheticScene {
  bool synthetic = false;
  CostShape shape = CostShape::kSkewed;
  std::uint64_t items = 0;
  std::string prefix;  // "synthetic" or "cascade"
};
inline SyntheticScene parse_synthetic_scene(const std::string& scene) {
  for (auto [prefix, shape] : {std::pair{"synthetic", CostShape::kSkewed}, std::pair{"cascade", CostShape::kCascade}}) {
    const std::string head = std::string(prefix) + ":";
    if (scene.rfind(head, 0) != 0) continue;
    SyntheticScene s{true, shape, 0, prefix};
    const std::string digits = scene.substr(head.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) {
      s.items = 0;  // the caller reports the range
    } else {
      s.items = std::stoull(digits);
    }
    return s;
  }
  return {};
}

// The cost of every item of every frame, in units: the skewed shape's light item is 1 (a heavy one `skew`), the
// cascade's mean item is 1. Built once per run, identically on every rank (integer hashing only, no library
// distributions).
class SyntheticCost {
 public:
  static constexpr int kFocusLevels = 2;  // the zoom's target: the coarsest splits are the most uneven
  static constexpr int kMovingLevels = 12;
  static constexpr std::uint64_t kSeed = 0x5EEDCA5CADEull;

  SyntheticCost(CostShape shape, ItemId n, int frames, std::uint32_t skew) : shape_(shape), n_(n), skew_(skew) {
    if (n == 0) throw std::invalid_argument("synthetic cost: no items");
    if (shape_ == CostShape::kCascade) {
      units_.resize(static_cast<std::size_t>(frames) * n);
      for (int f = 0; f < frames; ++f) fill_cascade(f, &units_[static_cast<std::size_t>(f) * n]);
    }
  }

  double units(int frame, ItemId id) const noexcept {
    if (shape_ == CostShape::kSkewed) return synthetic_heavy(frame, id, n_) ? skew_ : 1.0;
    return units_[static_cast<std::size_t>(frame) * n_ + id];
  }
  CostShape shape() const noexcept { return shape_; }
  ItemId items() const noexcept { return n_; }

 private:
  static std::uint64_t mix(std::uint64_t x) noexcept {  // SplitMix64's finalizer (Steele, Lea & Flood, 2014)
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }
  static double unit_interval(std::uint64_t x) noexcept { return static_cast<double>(x >> 11) * 0x1.0p-53; }

  // Splits [0, n) recursively (heap-numbered nodes, depth-first with an explicit stack).
  void fill_cascade(int frame, float* out) const {
    struct Node {
      ItemId lo, hi;
      double mass;
      std::uint64_t id;
      int depth;
    };
    std::vector<Node> stack{{0, n_, static_cast<double>(n_), 1, 0}};
    while (!stack.empty()) {
      const Node node = stack.back();
      stack.pop_back();
      if (node.hi - node.lo == 1) {
        out[node.lo] = static_cast<float>(node.mass);
        continue;
      }
      const std::uint64_t h = mix(kSeed ^ mix(node.id));
      double p;
      if (node.depth < kMovingLevels) {
        const double phase = 2 * 3.141592653589793 * unit_interval(mix(h));
        p = (node.depth < kFocusLevels ? 0.8 : 0.65) + 0.1 * std::sin(phase + 0.3 * frame);
      } else {
        p = 0.5 + 0.05 * (unit_interval(mix(h + 1)) - 0.5);
      }
      if ((h & 1) != 0) p = 1 - p;
      const ItemId mid = node.lo + (node.hi - node.lo) / 2;
      stack.push_back({node.lo, mid, node.mass * p, 2 * node.id, node.depth + 1});
      stack.push_back({mid, node.hi, node.mass * (1 - p), 2 * node.id + 1, node.depth + 1});
    }
  }

  CostShape shape_;
  ItemId n_;
  double skew_;
  std::vector<float> units_;  // cascade: frames x n
};

}  // namespace frontsteal::mpi
