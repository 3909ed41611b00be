// scale.hpp — the loss account, simulated: its constants taken from one measured main-job run (the calibration
// set), every term predicted for held-out runs and compared term by term, and the account predicted for more
// workers than the machine has, with the term that grows first named.
//
// What the simulator has of the account (simulator.hpp, SimulatedAccount): the items' work (the cost trace, times
// the measured inflation of P busy cores), the scheduler's per-item claim, the harness's checks, each worker's
// wake-up, the search and the steals (line transfers and fences of the protocol's accesses), the termination
// (the last worker's end and the join). Not modelled: time off the CPU (the measured shares are compared with it
// put back into the terms it was taken from), the wait at T4 (folded into steal), cache effects between items.
//
// The constants from the calibration set's measured account, per scheduler model: the per-item claim and checks
// (the harness's sampled timings), the wake-up of worker w (median over its rows), the join (the median over rows
// of the smallest worker termination per frame), and the work's inflation at each measured P. Beyond the measured
// workers a further worker wakes on an idle core of its own, in parallel with the others, the kernel's wake of one
// more thread later (Overheads::extra_worker_ns, ASSUMED), and the inflation is the largest measured P's: both
// can be given instead (scale_command: --inflation, --wake-us), e.g. from a measurement on a larger machine.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "papers/calibration.hpp"
#include "papers/cost_trace.hpp"
#include "papers/validation.hpp"

namespace frontsteal::papers {

// The account's terms the simulator predicts, in report order.
inline constexpr std::array<const char*, 7> kSimulatedTerms{"work",   "claim", "checks",     "wake",
                                                            "search", "steal", "termination"};

struct AccountConstants {
  Overheads overheads;                                 // the microbenchmarks' constants with the account's set
  std::map<WorkerId, double> inflation;                // per P: the work's inflation against the serial loop
  std::map<WorkerId, std::vector<double>> core_speed;  // per P: each worker's time for the same work over the mean
                                                       // (the limit arm's copies: the cores differ in speed)
  double inflation_at(WorkerId p) const;               // the given P's, else the largest P below it, else 1
};

// The constants of the calibration set (which must hold accounts: frontsteal.json schema 4). Throws
// std::runtime_error naming the set when it has none.
AccountConstants account_constants(const MeasuredSet& calibration, Overheads base);

// What the simulation predicts for `scheduler` at P on `trace` (times trace_scale): the shares of P x T by term
// name, and the path's time.
struct PredictedAccount {
  std::map<std::string, double> shares;
  double path_ns = 0;
};
PredictedAccount predict_account(const CostTrace& trace, double trace_scale, const AccountConstants& c,
                                 const std::string& scheduler, WorkerId p, std::uint64_t seed);

// A measured account as the simulation can be compared with: off-CPU time put back into the terms it was taken
// from, the wait at T4 added to steal, unaccounted left out.
std::map<std::string, double> comparable_shares(const MeasuredAccount& m);

// One held-out row, term by term.
struct TermComparison {
  std::string set, scheduler;
  WorkerId workers = 0;
  std::map<std::string, double> measured, predicted;
  std::vector<std::string> largest;  // the row's two largest measured terms
  // 100 x (predicted - measured) / measured; NaN where the measured share is below 0.2 % of P x T.
  double error_pct(const std::string& term) const;
};

// One point of the sweep beyond the machine: a scheduler at P on a trace.
struct ScalePoint {
  std::string trace, scheduler;
  WorkerId workers = 0;
  std::map<std::string, double> shares;
  double path_ns = 0;
  double limit_efficiency = 0;     // the work's share: the limit is P copies of the same work at the same inflation
  double critical_path_bound = 1;  // critical_path_bound(trace, P)
  std::string largest_loss;        // the largest term but work
};

// The best efficiency any schedule of whole items can reach at P on `trace`: per frame the work over P cannot end
// before the frame's largest item does, so Σ_f (W_f / P) / Σ_f max(W_f / P, largest item of f). A frame whose
// single costliest surface takes more than W_f / P caps every scheduler (a critical path of one item).
double critical_path_bound(const CostTrace& trace, WorkerId p);

// P = 1, 2, 4 ... max_p for every scheduler with a model, on one trace.
std::vector<ScalePoint> sweep(const CostTrace& trace, const std::string& trace_name, double trace_scale,
                              const AccountConstants& c, const std::vector<std::string>& schedulers, WorkerId max_p,
                              std::uint64_t seed);

}  // namespace frontsteal::papers
