// synthetic_machine.hpp — a machine whose speed changes under the program, with the truth known: series for
// testing the measurement method (its intervals' coverage, the bias of a fixed order, the calibration rates)
// without timing luck.
//
// The machine's slowness is a log-factor s(t) over simulated time: a steady drift, a step change, one burst,
// and a fast wander (an Ornstein-Uhlenbeck process: the VMs' speed changes within a 0.5 s path and between
// the cells of one round, docs/measurement.md). An arm of cost c started at time t takes
// c * exp(s(t) + e), e ~ N(0, run_noise_sd^2) (plus, in a share outlier_rate of the runs, N(0, outlier_sd^2):
// the heavy tails the real machines show); the probe taken just before it reads exp(k s(t) + u), with k how
// much of the machine's change the probe sees. Arms run one after another, so a round's order decides when
// each one runs — which is what makes a fixed order biased under drift.
//
// Instances: each arm runs as one instance for `rounds_per_instance` consecutive rounds, then a fresh one (0: one
// instance for the whole run); each instance carries a fixed log-offset ~ N(0, instance_sd^2) — the
// few-per-cent difference two copies of the same code show for as long as they live (paired_analysis.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "measure/round_order.hpp"

namespace frontsteal::measure {

struct SpeedModel {
  double drift_per_s = 0;                          // d s / dt: the steady drift (0.001 = 0.1 % slower each second)
  double step_at_s = -1, step = 0;                 // s jumps by `step` at that time (negative time: none)
  double burst_at_s = -1, burst_s = 0, burst = 0;  // s is raised by `burst` during [at, at + burst_s)
  double wander_sd = 0, wander_tau_s = 1;          // the fast wander's stationary spread and time constant
  double run_noise_sd = 0.01;                      // each run's own noise
  double outlier_rate = 0, outlier_sd = 0;         // a run hit by a change of speed inside it: extra noise, this often
  double probe_noise_sd = 0.005;                   // the probe's own noise
  double probe_tracking = 1.0;                     // k: the share of s the probe sees
  double instance_sd = 0;                          // each instance's fixed offset
  std::size_t rounds_per_instance = 0;             // an arm's fresh instance every this many rounds (0: one per run)
};

struct SyntheticRun {
  std::vector<std::vector<double>> time, probe;  // [arm][round], seconds and the probe's reading
  std::vector<int> block;                        // [round]
  std::vector<int> instance;                     // [round]: every arm's instance id (-1: instances not modelled)
};

// `rounds` rounds of the arms (costs in seconds; round k covers block k % blocks, whose cost is scaled by
// block_scale[block] when given), each round in the order `kind` gives.
SyntheticRun simulate_rounds(const SpeedModel& model, const std::vector<double>& arm_cost_s, std::size_t rounds,
                             std::size_t blocks, OrderKind kind, std::uint64_t seed,
                             const std::vector<double>& block_scale = {});

// The pairs of arm `candidate` against arm `reference` in a run.
std::vector<RoundPair> pairs_of(const SyntheticRun& run, std::size_t candidate, std::size_t reference);

}  // namespace frontsteal::measure
