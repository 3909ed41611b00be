// publication_scenarios.hpp — greedy rendering's publication-and-reclamation scenarios, as data: one source for
// the model checker (publication_suite.cpp), the stress driver (stress/publication_stress.hpp) and the tests.
//
// Roles: a pusher (draws every component once per update), a driver that is also tessellator 0 (prepares each
// frame), and tessellator 1. A component's surfaces are spread over both tessellators, so the component
// is complete only when the second of them finishes: the case a torn component needs.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace frontsteal::model {

struct PublicationSpec {
  std::string_view name;
  std::string_view checks;                             // one line: the property this scenario exists for
  std::vector<std::vector<std::uint32_t>> components;  // per component: the tessellator (0 or 1) of each surface
  std::uint32_t slots;
  std::uint32_t frames;
  std::uint32_t updates;  // pusher updates
};

inline constexpr std::uint32_t kMaxPublicationComponents = 2;
inline constexpr std::uint32_t kMaxPublicationSlots = 3;
inline constexpr std::uint32_t kMaxPublicationSurfaces = 2;  // per component

inline const std::vector<PublicationSpec>& publication_scenarios() {
  static const std::vector<PublicationSpec> all{
      {"two_slots_reuse",
       "two slots: every frame after the second reuses a slot the pusher may hold",
       {{0, 1}},
       2,
       3,
       3},
      {"three_slots_two_components",
       "three slots, two components (one split, one whole): no torn component",
       {{0, 1}, {0}},
       3,
       3,
       2},
      {"pusher_gone",
       "the pusher stops after one update: the driver still finds free slots (no deadlock)",
       {{1, 0}},
       2,
       3,
       1},
  };
  return all;
}

}  // namespace frontsteal::model
