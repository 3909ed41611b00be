// static_assignment.hpp — the lists of the static schedulers (paper §3).
//
//   round_robin_assignment   item i to worker i mod P: the paper's baseline.
//   morton_deal_assignment   sort items by the Morton code of their centre, deal them round robin: nearby
//                            primitives land on different workers; cheap and deterministic.
//   annealed_assignment      the paper's graph partition: vertex weight = estimated cost, edge weight =
//                            1 / distance, subgraph cost = Σ over edges inside it of W_e (W_v1 + W_v2);
//                            minimized by simulated annealing under a balance penalty, starting from the
//                            Morton deal. The paper's graph is complete; ours keeps, per item, the edges to
//                            its `neighbours` nearest items in Morton order (far edges weigh ~1/distance ≈ 0,
//                            and the complete graph's n² edges do not fit 15,906 items in a frame's budget).
#pragma once

#include <cstdint>
#include <vector>

#include "schedulers/scheduler.hpp"
#include "schedulers/static_scheduler.hpp"

namespace frontsteal::sched {

Assignment round_robin_assignment(ItemId items, WorkerId workers);
Assignment morton_deal_assignment(ItemId items, WorkerId workers, const WorkloadHints& hints);

struct AnnealingOptions {
  std::uint64_t seed = 1;
  int neighbours = 16;         // edges per item (nearest in Morton order, each side half)
  double moves_per_item = 40;  // proposals = moves_per_item × items, at most max_moves
  std::uint64_t max_moves = 4'000'000;
  double balance_weight = 50;  // penalty per unit of Σ_w ((L_w − L̄) / L̄)², relative to the initial edge cost
};

struct AnnealingReport {
  double initial_edge_cost = 0, final_edge_cost = 0;  // Σ_w Σ_{e inside w} W_e (W_v1 + W_v2)
  double initial_imbalance = 0, final_imbalance = 0;  // max_w L_w / L̄ of the estimated costs
  std::uint64_t proposals = 0, accepted = 0;
};

Assignment annealed_assignment(ItemId items, WorkerId workers, const WorkloadHints& hints,
                               const AnnealingOptions& options = {}, AnnealingReport* report = nullptr);

// max_w L_w / L̄ of the estimated costs (1.0 = perfect balance; equal costs when hints.costs is empty).
double estimated_imbalance(const Assignment& a, const WorkloadHints& hints);

}  // namespace frontsteal::sched
