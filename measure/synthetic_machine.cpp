// synthetic_machine.cpp — the simulated machine and its rounds (synthetic_machine.hpp).
#include "measure/synthetic_machine.hpp"

#include <cmath>

#include "measure/paired_comparison.hpp"

namespace frontsteal::measure {

namespace {

// A standard normal deviate (Box-Muller on two uniforms from splitmix64).
double normal(stats::SplitMix64& rng) {
  const double u1 = (static_cast<double>(rng.next() >> 11) + 0.5) / 9007199254740992.0;
  const double u2 = static_cast<double>(rng.next() >> 11) / 9007199254740992.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

class Machine {
 public:
  Machine(const SpeedModel& m, std::uint64_t seed) : m_(m), rng_(seed) {}
  // s(t) at the current time, after advancing the wander to it.
  double slowness() const {
    double s = m_.drift_per_s * t_ + wander_;
    if (m_.step_at_s >= 0 && t_ >= m_.step_at_s) s += m_.step;
    if (m_.burst_at_s >= 0 && t_ >= m_.burst_at_s && t_ < m_.burst_at_s + m_.burst_s) s += m_.burst;
    return s;
  }
  void advance(double dt) {
    if (m_.wander_sd > 0) {
      const double keep = std::exp(-dt / m_.wander_tau_s);
      wander_ = wander_ * keep + m_.wander_sd * std::sqrt(1.0 - keep * keep) * normal(rng_);
    }
    t_ += dt;
  }
  double noise(double sd) { return sd > 0 ? sd * normal(rng_) : 0.0; }
  double uniform() { return static_cast<double>(rng_.next() >> 11) / 9007199254740992.0; }

 private:
  const SpeedModel& m_;
  stats::SplitMix64 rng_;
  double t_ = 0, wander_ = 0;
};

}  // namespace

SyntheticRun simulate_rounds(const SpeedModel& model, const std::vector<double>& arm_cost_s, std::size_t rounds,
                             std::size_t blocks, OrderKind kind, std::uint64_t seed,
                             const std::vector<double>& block_scale) {
  SyntheticRun run;
  const std::size_t arms = arm_cost_s.size();
  run.time.assign(arms, std::vector<double>(rounds));
  run.probe.assign(arms, std::vector<double>(rounds));
  if (blocks == 0) blocks = 1;
  // The machine draws from a stream of its own: the orders come from round_order(seed, round).
  Machine machine(model, seed ^ 0x6a09'e667'f3bc'c909ull);
  // The instances' offsets from a stream of their own, so that adding them leaves the rest of a series as it was.
  stats::SplitMix64 instance_rng(seed ^ 0xbb67'ae85'84ca'a73bull);
  std::vector<double> offset(arms, 0.0);
  for (std::size_t k = 0; k < rounds; ++k) {
    const int block = static_cast<int>(k % blocks);
    run.block.push_back(block);
    if (model.instance_sd > 0) {
      const std::size_t per = model.rounds_per_instance ? model.rounds_per_instance : rounds;
      if (k % per == 0) {
        for (double& o : offset) o = model.instance_sd * normal(instance_rng);
      }
      run.instance.push_back(static_cast<int>(k / per));
    } else {
      run.instance.push_back(-1);
    }
    const double scale = block_scale.empty() ? 1.0 : block_scale[static_cast<std::size_t>(block) % block_scale.size()];
    for (std::size_t a : round_order(arms, seed, k, kind)) {
      const double s = machine.slowness();
      run.probe[a][k] = std::exp(model.probe_tracking * s + machine.noise(model.probe_noise_sd));
      double e = machine.noise(model.run_noise_sd);
      if (model.outlier_rate > 0 && machine.uniform() < model.outlier_rate) e += machine.noise(model.outlier_sd);
      const double t = arm_cost_s[a] * scale * std::exp(s + e + offset[a]);
      run.time[a][k] = t;
      machine.advance(t);
    }
  }
  return run;
}

std::vector<RoundPair> pairs_of(const SyntheticRun& run, std::size_t candidate, std::size_t reference) {
  std::vector<RoundPair> out;
  for (std::size_t k = 0; k < run.block.size(); ++k) {
    out.push_back({run.time[candidate][k], run.time[reference][k], run.block[k], run.probe[candidate][k],
                   run.probe[reference][k], run.instance[k], run.instance[k]});
  }
  return out;
}

}  // namespace frontsteal::measure
