// hand_made_trace.hpp — a cost trace written by hand for the simulator's tests: costs[f][i] is item i's cost in
// frame f (ns); the items stand on a line, each estimated at 1.
#pragma once

#include <utility>
#include <vector>

#include "papers/cost_trace.hpp"

namespace frontsteal::papers::testing {

inline CostTrace hand_made_trace(std::vector<std::vector<double>> costs) {
  CostTrace t;
  t.scene = "hand-made";
  for (std::size_t i = 0; i < costs.at(0).size(); ++i) {
    t.centres.push_back({static_cast<double>(i), 0, 0});
    t.estimates.push_back(1);
  }
  t.cost_ns = std::move(costs);
  return t;
}

}  // namespace frontsteal::papers::testing
