// static_assignment.cpp — round robin, Morton deal and the annealed graph partition (see the header).
#include "schedulers/static_assignment.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace frontsteal::sched {
namespace {

double cost_of(const WorkloadHints& h, ItemId i) { return h.costs.empty() ? 1.0 : h.costs[i]; }

std::array<double, 3> centre_of(const WorkloadHints& h, ItemId i) {
  return h.centres.empty() ? std::array<double, 3>{static_cast<double>(i), 0, 0} : h.centres[i];
}

// 21 bits per axis, interleaved.
std::uint64_t spread_bits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Item ids sorted by the Morton code of their centres in the items' bounding box (ties by id).
std::vector<ItemId> morton_order(ItemId items, const WorkloadHints& hints) {
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (ItemId i = 0; i < items; ++i) {
    const auto c = centre_of(hints, i);
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
  }
  std::vector<std::pair<std::uint64_t, ItemId>> keyed(items);
  for (ItemId i = 0; i < items; ++i) {
    const auto c = centre_of(hints, i);
    std::uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double extent = hi[a] - lo[a];
      const double t = extent > 0 ? (c[a] - lo[a]) / extent : 0.0;
      code |= spread_bits(static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 2097151.0)) << a;
    }
    keyed[i] = {code, i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<ItemId> order(items);
  for (ItemId k = 0; k < items; ++k) order[k] = keyed[k].second;
  return order;
}

}  // namespace

Assignment round_robin_assignment(ItemId items, WorkerId workers) {
  Assignment a(workers);
  for (ItemId i = 0; i < items; ++i) a[i % workers].push_back(i);
  return a;
}

Assignment morton_deal_assignment(ItemId items, WorkerId workers, const WorkloadHints& hints) {
  Assignment a(workers);
  const std::vector<ItemId> order = morton_order(items, hints);
  for (ItemId k = 0; k < items; ++k) a[k % workers].push_back(order[k]);
  // Same sets, processed in id order: the model's memory order (Morton order costs cache misses, ~15% at P=1).
  for (auto& list : a) std::sort(list.begin(), list.end());
  return a;
}

double estimated_imbalance(const Assignment& a, const WorkloadHints& hints) {
  double total = 0, max_load = 0;
  for (const auto& list : a) {
    double load = 0;
    for (ItemId id : list) load += cost_of(hints, id);
    total += load;
    max_load = std::max(max_load, load);
  }
  return total > 0 ? max_load / (total / static_cast<double>(a.size())) : 1.0;
}

Assignment annealed_assignment(ItemId items, WorkerId workers, const WorkloadHints& hints,
                               const AnnealingOptions& options, AnnealingReport* report) {
  Assignment start = morton_deal_assignment(items, workers, hints);
  if (workers < 2 || items < 2) {
    if (report) *report = {};
    return start;
  }
  // The sparse load graph: each item's neighbours in Morton order, weight 1 / distance.
  const std::vector<ItemId> order = morton_order(items, hints);
  double diag = 0;
  {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (ItemId i = 0; i < items; ++i) {
      const auto c = centre_of(hints, i);
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    for (int a = 0; a < 3; ++a) diag += (hi[a] - lo[a]) * (hi[a] - lo[a]);
    diag = std::sqrt(diag);
  }
  const double min_distance = std::max(diag, 1e-300) * 1e-6;
  const int half = std::max(1, options.neighbours / 2);
  struct Edge {
    ItemId to;
    double weight;
  };
  std::vector<std::vector<Edge>> graph(items);
  for (ItemId k = 0; k < items; ++k) {
    const ItemId u = order[k];
    const auto cu = centre_of(hints, u);
    for (int d = 1; d <= half && k + d < items; ++d) {
      const ItemId v = order[k + d];
      const auto cv = centre_of(hints, v);
      const double dist = std::sqrt((cu[0] - cv[0]) * (cu[0] - cv[0]) + (cu[1] - cv[1]) * (cu[1] - cv[1]) +
                                    (cu[2] - cv[2]) * (cu[2] - cv[2]));
      const double w = 1.0 / std::max(dist, min_distance);
      graph[u].push_back({v, w});
      graph[v].push_back({u, w});
    }
  }

  std::vector<WorkerId> owner(items);
  std::vector<std::uint32_t> position(items);  // index of the item in its worker's list
  Assignment lists = std::move(start);
  std::vector<double> load(workers, 0.0);
  for (WorkerId w = 0; w < workers; ++w) {
    for (std::uint32_t k = 0; k < lists[w].size(); ++k) {
      owner[lists[w][k]] = w;
      position[lists[w][k]] = k;
      load[w] += cost_of(hints, lists[w][k]);
    }
  }
  double total_load = 0;
  for (double l : load) total_load += l;
  const double mean_load = std::max(total_load / workers, 1e-300);

  auto edge_cost = [&] {
    double c = 0;
    for (ItemId u = 0; u < items; ++u) {
      for (const Edge& e : graph[u]) {
        if (e.to > u && owner[e.to] == owner[u]) c += e.weight * (cost_of(hints, u) + cost_of(hints, e.to));
      }
    }
    return c;
  };
  // Σ over edges of u to items on worker w of W_e (W_u + W_v), u itself excluded.
  auto attachment = [&](ItemId u, WorkerId w, ItemId except) {
    double c = 0;
    for (const Edge& e : graph[u]) {
      if (e.to != except && owner[e.to] == w) c += e.weight * (cost_of(hints, u) + cost_of(hints, e.to));
    }
    return c;
  };
  const double initial_edges = edge_cost();
  const double edge_scale = initial_edges > 0 ? initial_edges : 1.0;
  auto imbalance_term = [&](double l) {
    const double r = (l - mean_load) / mean_load;
    return r * r;
  };

  std::mt19937_64 rng(options.seed);
  const std::uint64_t proposals =
      std::min<std::uint64_t>(options.max_moves, static_cast<std::uint64_t>(options.moves_per_item * items));
  // Temperature: from the mean |Δ| of a sample of proposals down to 1/1000 of it, geometrically.
  auto propose = [&](ItemId& v, ItemId& x) -> bool {
    const ItemId u = static_cast<ItemId>(rng() % items);
    if (graph[u].empty()) return false;
    v = graph[u][rng() % graph[u].size()].to;  // a neighbour of u ...
    if (owner[v] != owner[u]) return false;    // ... on u's worker: move it away (the paper's heuristic)
    WorkerId q = static_cast<WorkerId>(rng() % (workers - 1));
    if (q >= owner[v]) ++q;
    if (lists[q].empty()) return false;
    x = lists[q][rng() % lists[q].size()];  // swapped with a random item of worker q
    return true;
  };
  auto delta = [&](ItemId v, ItemId x) {
    const WorkerId p = owner[v], q = owner[x];
    const double edges = attachment(v, q, x) - attachment(v, p, v) + attachment(x, p, v) - attachment(x, q, x);
    const double cv = cost_of(hints, v), cx = cost_of(hints, x);
    const double balance = imbalance_term(load[p] - cv + cx) + imbalance_term(load[q] - cx + cv) -
                           imbalance_term(load[p]) - imbalance_term(load[q]);
    return edges / edge_scale + options.balance_weight * balance;
  };
  auto apply = [&](ItemId v, ItemId x) {
    const WorkerId p = owner[v], q = owner[x];
    std::swap(lists[p][position[v]], lists[q][position[x]]);
    std::swap(position[v], position[x]);
    owner[v] = q;
    owner[x] = p;
    const double cv = cost_of(hints, v), cx = cost_of(hints, x);
    load[p] += cx - cv;
    load[q] += cv - cx;
  };
  double t0 = 0;
  {
    int sampled = 0;
    for (int k = 0; k < 4000 && sampled < 1000; ++k) {
      ItemId v, x;
      if (!propose(v, x)) continue;
      t0 += std::abs(delta(v, x));
      ++sampled;
    }
    t0 = sampled > 0 ? t0 / sampled : 1.0;
    if (!(t0 > 0)) t0 = 1e-9;
  }
  const double cooling = std::pow(1e-3, 1.0 / std::max<double>(1.0, static_cast<double>(proposals)));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double temperature = t0;
  AnnealingReport r;
  r.initial_edge_cost = initial_edges;
  r.initial_imbalance = estimated_imbalance(lists, hints);
  for (std::uint64_t k = 0; k < proposals; ++k, temperature *= cooling) {
    ItemId v, x;
    if (!propose(v, x)) continue;
    ++r.proposals;
    const double d = delta(v, x);
    if (d <= 0 || uniform(rng) < std::exp(-d / temperature)) {
      apply(v, x);
      ++r.accepted;
    }
  }
  r.final_edge_cost = edge_cost();
  r.final_imbalance = estimated_imbalance(lists, hints);
  if (report) *report = r;
  for (auto& list : lists) std::sort(list.begin(), list.end());  // memory order of the model within a list
  return lists;
}

}  // namespace frontsteal::sched
