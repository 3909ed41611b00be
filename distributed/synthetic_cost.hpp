// synthetic_cost.hpp — the skewed synthetic workload's cost shape, shared by frontsteal-mpi (synthetic:N) and
// the distributed simulator: a fifth of the ids are `skew` times heavier, and that window moves with the
// frame so last frame's allocation is never quite right (the case stealing exists for).
#pragma once

#include <cstdint>

#include "core/id_range.hpp"

namespace frontsteal::mpi {

inline bool synthetic_heavy(int frame, ItemId id, ItemId n) noexcept {
  const std::uint64_t shifted = (std::uint64_t{id} + std::uint64_t(frame) * (n / 37 + 1)) % n;
  return shifted * 5 >= std::uint64_t{n} * 4;
}

}  // namespace frontsteal::mpi
