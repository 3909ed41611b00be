// paired_analysis.hpp — is a candidate faster than, slower than, or equivalent to a reference, within a declared
// margin, from rounds in which both ran?
//
// The unit is the round: every arm of the experiment runs once per round, in a fresh random order
// (round_order.hpp), so a drift of the machine's speed hits both members of a pair about alike, and hits no arm
// more than another on average. Per round r the analysis takes the log-ratio
//   d_r = log(T_candidate[r]) - log(T_reference[r])
// (Kalibera & Jones, ISMM 2013: the round is the sample; ratios are compared on the log scale). Rounds are
// grouped in blocks (the segment of the camera path a round covered; rounds of one block ran the same frames,
// so their ratios share an expected value): d_r = mu + beta_block + e_r, with the block effects removed before
// the spread is taken (df = rounds - blocks). The estimate of mu is Huber's M-estimate (robust: on these
// machines a few rounds are off by 20-30 % when the speed changed inside one arm's run) or, with
// Estimator::kMean, the mean; the interval is Student's t on it (measure/student_t.hpp) with Huber's sandwich
// standard error; the shown ratio is exp of the estimate.
//
// The covariate (regression adjustment, "CUPED": Deng, Xu, Kohavi & Walker, WSDM 2013): the CPU speed probe
// (cpu_speed_probe.hpp) timed on the harness thread just BEFORE each arm ran, c_r = log(probe_cand) -
// log(probe_ref). Taken before the arm, it cannot depend on which arm runs (the condition for an unbiased
// adjustment); its expected value is 0 because the order is random. The adjusted estimate regresses d on c
// within blocks (slope theta, df = rounds - blocks - 1) and removes theta * mean(c); its variance is the
// residual variance times (1/N + mean(c)^2 / Sxx). Both intervals are reported, with the share of the
// variance the covariate removed; `Settings::adjust_for_probe` chooses which one decides.
//
// Verdicts against a margin m (default 2 %), L = log(1 + m), on the chosen interval [lo, hi]:
//   faster      hi < -L          (the whole interval beyond the margin, candidate faster)
//   slower      lo >  L
//   equivalent  -L < lo and hi < L   (the whole interval inside the margin)
//   inconclusive otherwise — with the rounds a run of this noise would need to decide
// `differs` says the interval excludes 0 (a difference of either sign found, whatever its size): a planted
// slowdown smaller than the margin can be found (differs) without being called slower.
//
// Instances (clusters). Two instances of the same code can differ by a few per cent for as long as they live
// (where their memory landed, which threads they own: Mytkowicz et al., ASPLOS 2009; Curtsinger & Berger,
// ASPLOS 2013), so rounds run by one instance are not independent. When a round names the instances that ran
// it, rounds sharing an instance of either arm form one cluster, and the standard error is the cluster-robust
// sandwich (Liang & Zeger 1986; Cameron & Miller, J. Human Resources 2015): the rounds' influences summed per
// cluster, squared and summed, times N / (N - h), with df = G (1 - h / N) (- 1 with the covariate), where G
// counts the clusters and h = sum over clusters g and blocks b of n_gb^2 / n_b is what the block effects take
// from the cluster sums. In the main job's design (G clusters, each a stretch of one of G / E passes) that is
// G / (G - E) with df = G - E; with no instances named every round is its own cluster and this is exactly the
// round-level interval above (h = B).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace frontsteal::measure {

// One round of a comparison: both arms' times by the harness's clock (any unit, the same for both), the
// round's block, the CPU speed probe taken just before each arm (0: not measured), and which instance of each
// arm ran it (-1: none, or a fresh one every round).
struct RoundPair {
  double candidate = 0, reference = 0;
  int block = 0;
  double candidate_probe = 0, reference_probe = 0;
  int candidate_instance = -1, reference_instance = -1;
};

// One arm's record over the rounds it ran in: per round, the round's id (increasing), its time, the probe
// before it, the round's block and the instance of the arm that ran it (-1: none). An arm need not run in every
// round of a run (the main job's rounds each hold the arms of one P), so pairs are matched by round id.
struct ArmRounds {
  std::vector<std::size_t> round;
  std::vector<double> time, probe;
  std::vector<int> block, instance;
  void add(std::size_t id, double t, double p, int b, int inst = -1) {
    round.push_back(id);
    time.push_back(t);
    probe.push_back(p);
    block.push_back(b);
    instance.push_back(inst);
  }
  std::size_t size() const { return time.size(); }
};

// The pairs of two arms over the rounds both ran in.
inline std::vector<RoundPair> pair_rounds(const ArmRounds& candidate, const ArmRounds& reference) {
  std::vector<RoundPair> out;
  std::size_t j = 0;
  for (std::size_t i = 0; i < candidate.size(); ++i) {
    while (j < reference.size() && reference.round[j] < candidate.round[i]) ++j;
    if (j == reference.size()) break;
    if (reference.round[j] != candidate.round[i]) continue;
    out.push_back({candidate.time[i], reference.time[j], candidate.block[i], candidate.probe[i], reference.probe[j],
                   candidate.instance[i], reference.instance[j]});
  }
  return out;
}

enum class Decision { kFaster, kSlower, kEquivalent, kInconclusive, kTooFewRounds };

const char* to_string(Decision d) noexcept;

// How the location of the log-ratios is estimated: Huber's M-estimate (robust to the few rounds in which the
// machine changed speed inside one arm's run), or the mean (least squares; the textbook t interval).
enum class Estimator { kHuber, kMean };
const char* to_string(Estimator e) noexcept;

struct Settings {
  double margin = 0.02;          // m: equivalence margin, as a fraction of time
  double confidence = 0.95;      // of every interval
  bool adjust_for_probe = true;  // the verdict from the covariate-adjusted interval (when it can be computed)
  Estimator estimator = Estimator::kHuber;
};

// An interval on the log-ratio scale, with its per-round spread.
struct LogInterval {
  double estimate = 0, low = 0, high = 0;
  double sd = 0;  // spread of one round's log-ratio (within blocks; after the covariate, if adjusted); with
                  // clusters, the spread that gives the cluster-robust standard error at this many rounds
  double se = 0;  // standard error of the estimate
  double df = 0;
  bool valid = false;
  double ratio() const { return std::exp(estimate); }
  double ratio_low() const { return std::exp(low); }
  double ratio_high() const { return std::exp(high); }
  double effect_pct() const { return 100.0 * (std::exp(estimate) - 1.0); }  // change in time; negative = faster
  bool contains(double log_ratio) const { return low <= log_ratio && log_ratio <= high; }
};

struct PairedResult {
  std::size_t rounds = 0, blocks = 0;
  std::size_t clusters = 0;     // groups of rounds that shared an instance (= rounds when none is named)
  LogInterval raw, adjusted;    // adjusted.valid: the probe was measured for every round and df allows it
  double probe_slope = 0;       // theta
  double variance_removed = 0;  // 1 - adjusted.sd^2 / raw.sd^2 (negative: the covariate cost degrees of freedom)
  bool uses_adjusted = false;   // the verdict comes from `adjusted`
  Decision decision = Decision::kTooFewRounds;
  bool differs = false;      // the chosen interval excludes 0
  double rounds_needed = 0;  // to decide at this noise (0: decided; +inf: the estimate sits on the margin)
  double mde_pct = 0;        // smallest change this run finds with 80 % power (two-sided, at `confidence`)
  double margin = 0;
  const LogInterval& chosen() const { return uses_adjusted ? adjusted : raw; }
};

// The analysis of one comparison. Pairs with a non-positive time are left out.
PairedResult analyze_pairs(const std::vector<RoundPair>& pairs, const Settings& settings = {});

// Rounds a paired comparison needs so that a true change of `effect` (as a fraction of time, e.g. 0.02) is found
// with 80 % power at 95 %, given the spread `sd` of one round's log-ratio: n = 7.85 (sd / log(1 + effect))^2 + 2.
double rounds_for_power(double sd, double effect);
// Rounds that let the verdict decide with 80 % power: an equal pair's 95 % interval inside +-margin (half-width
// below L = log(1 + margin) with probability 0.8: n = (1.96 + 1.28)^2 (sd / L)^2 + 2 = 10.5 (sd / L)^2 + 2), which
// is also what a change of twice the margin needs to be called faster or slower.
double rounds_to_decide(double sd, double margin);

// "faster -11.6 % [-15.0, -8.1]" style text for a result (the chosen interval, in % change of time).
std::string describe(const PairedResult& r);

}  // namespace frontsteal::measure
