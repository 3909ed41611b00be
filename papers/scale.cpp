// scale.cpp — the simulated loss account (scale.hpp).
#include "papers/scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "papers/simulator.hpp"
#include "schedulers/static_assignment.hpp"

namespace frontsteal::papers {
namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

ModelCosts& costs_of(Overheads& o, Model m) {
  switch (m) {
    case Model::static_list: return o.static_list;
    case Model::queue: return o.queue;
    case Model::stealing: return o.stealing;
    case Model::chase_lev: return o.chase_lev;
  }
  return o.stealing;
}

}  // namespace

double AccountConstants::inflation_at(WorkerId p) const {
  auto it = inflation.upper_bound(p);
  if (it == inflation.begin()) return 1.0;
  return std::prev(it)->second;
}

AccountConstants account_constants(const MeasuredSet& cal, Overheads base) {
  AccountConstants c;
  c.overheads = std::move(base);
  Overheads& o = c.overheads;
  std::map<Model, std::pair<WorkerId, double>> claim;  // per model: the largest P's claim per item
  std::vector<double> checks, joins;
  std::map<WorkerId, std::vector<double>> wake, inflation;
  for (const MeasuredCell& cell : cal.cells) {
    if (!cell.account) continue;
    const MeasuredAccount& a = *cell.account;
    const double frames = static_cast<double>(std::max<std::uint64_t>(a.frames, 1));
    if (const std::optional<Model> m = model_of(cell.scheduler)) {
      auto& [p, ns] = claim[*m];
      if (cell.workers >= p) {
        p = cell.workers;
        ns = a.claim_per_item_ns;
      }
    }
    checks.push_back(a.checks_per_item_ns);
    for (std::size_t w = 0; w < a.wake_ms.size(); ++w)
      wake[static_cast<WorkerId>(w)].push_back(1e6 * a.wake_ms[w] / frames);
    if (!a.termination_ms.empty()) {
      joins.push_back(1e6 * *std::min_element(a.termination_ms.begin(), a.termination_ms.end()) / frames);
    }
    inflation[cell.workers].push_back(a.inflation);
  }
  if (checks.empty()) {
    throw std::runtime_error("set " + cal.name + " has no loss account (frontsteal.json schema 4 is needed)");
  }
  for (const auto& [m, at] : claim) costs_of(o, m).item_ns = at.second;
  o.checks_ns = median_of(checks);
  o.wake_by_worker_ns.clear();
  for (const auto& [w, values] : wake) o.wake_by_worker_ns.push_back(median_of(values));
  o.join_ns = median_of(joins);
  for (const auto& [p, values] : inflation) c.inflation[p] = median_of(values);
  c.core_speed = cal.limit_copy_time;
  return c;
}

PredictedAccount predict_account(const CostTrace& trace, double trace_scale, const AccountConstants& c,
                                 const std::string& scheduler, WorkerId p, std::uint64_t seed) {
  const std::optional<Model> m = model_of(scheduler);
  if (!m) throw std::invalid_argument("no simulator model for " + scheduler);
  CostTrace scaled = trace;
  const double scale = trace_scale * c.inflation_at(p);
  for (auto& frame : scaled.cost_ns) {
    for (double& cost : frame) cost *= scale;
  }
  const sched::Assignment rr = sched::round_robin_assignment(static_cast<ItemId>(trace.surfaces()), p);
  const auto speed = c.core_speed.find(p);
  const SimulationOptions so{.model = *m,
                             .workers = p,
                             .assignment = &rr,
                             .seed = seed,
                             .worker_slowdown = speed != c.core_speed.end() && speed->second.size() == p
                                                    ? speed->second
                                                    : std::vector<double>{}};
  const SimulatedRun run = simulate(scaled, c.overheads, so);
  if (run.audit_failures) throw std::logic_error("scale: the simulation of " + scheduler + " failed its audit");
  const SimulatedAccount& a = run.account;
  return {{{"work", a.share(a.work)},
           {"claim", a.share(a.claim)},
           {"checks", a.share(a.checks)},
           {"wake", a.share(a.wake)},
           {"search", a.share(a.search)},
           {"steal", a.share(a.steal)},
           {"termination", a.share(a.termination)}},
          run.path_ns};
}

std::map<std::string, double> comparable_shares(const MeasuredAccount& m) {
  std::map<std::string, double> raw = m.shares_with_off_cpu();
  std::map<std::string, double> out;
  for (const char* t : kSimulatedTerms) out[t] = raw.count(t) ? raw.at(t) : 0.0;
  if (raw.count("wait")) out["steal"] += raw.at("wait");
  return out;
}

double TermComparison::error_pct(const std::string& term) const {
  const double m = measured.count(term) ? measured.at(term) : 0.0;
  const double p = predicted.count(term) ? predicted.at(term) : 0.0;
  if (m < 0.002) return std::numeric_limits<double>::quiet_NaN();
  return 100.0 * (p - m) / m;
}

double critical_path_bound(const CostTrace& trace, WorkerId p) {
  double ideal = 0, bound = 0;
  for (const std::vector<double>& frame : trace.cost_ns) {
    double total = 0, largest = 0;
    for (const double c : frame) {
      total += c;
      largest = std::max(largest, c);
    }
    ideal += total / p;
    bound += std::max(total / p, largest);
  }
  return bound > 0 ? ideal / bound : 1.0;
}

std::vector<ScalePoint> sweep(const CostTrace& trace, const std::string& trace_name, double trace_scale,
                              const AccountConstants& c, const std::vector<std::string>& schedulers, WorkerId max_p,
                              std::uint64_t seed) {
  std::vector<ScalePoint> out;
  for (const std::string& s : schedulers) {
    for (WorkerId p = 1; p <= max_p; p *= 2) {
      PredictedAccount predicted = predict_account(trace, trace_scale, c, s, p, seed);
      ScalePoint pt{trace_name, s, p, std::move(predicted.shares), predicted.path_ns, 0, 1, ""};
      pt.limit_efficiency = pt.shares.at("work");
      pt.critical_path_bound = critical_path_bound(trace, p);
      double largest = -1;
      for (const auto& [term, share] : pt.shares) {
        if (term != "work" && share > largest) {
          largest = share;
          pt.largest_loss = term;
        }
      }
      out.push_back(std::move(pt));
    }
  }
  return out;
}

}  // namespace frontsteal::papers
