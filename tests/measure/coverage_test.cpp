// coverage_test.cpp — how often the 95 % paired t interval holds the planted truth on synthetic machines that
// drift, step, burst, wander and have heavy-tailed rounds, for both estimators of the location (Huber's
// M-estimate, the default, and the mean), how often identical arms get a false verdict, what the probe
// adjustment adds, and how much narrower Huber's interval is where the rounds have heavy tails; counted with
// CalibrationTally, whose counters are checked first on hand-made results.
//
// Every run has three arms in random order: A (0.3 s), A's twin (the same cost: truth 0) and A x 1.05 (truth
// log 1.05), 30 rounds over 4 blocks of different lengths. 1000 fixed seeds per scenario put the standard error
// of a 95 % coverage at 0.7 points, so the bands below (about 3.5 standard errors wide on either side) catch an
// interval that is too narrow or too wide without depending on sampling luck. Every test sets the estimator
// explicitly: the mean's bands describe the least-squares t interval, Huber's the default.
#include "measure/calibration_tally.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "measure/round_order.hpp"
#include "measure/synthetic_machine.hpp"

namespace ms = frontsteal::measure;

namespace {

constexpr std::size_t kSeeds = 1000;
constexpr double kPlanted = 0.05;

struct Tallies {
  ms::CalibrationTally twin, planted;
  double variance_removed_sum = 0;  // over both comparisons of every seed
  std::size_t adjusted_used = 0;
  std::vector<double> half_width;  // of the chosen interval (log scale), both comparisons of every seed
  double mean_variance_removed() const { return variance_removed_sum / (2.0 * static_cast<double>(twin.experiments)); }
  double median_half_width() const {
    std::vector<double> h = half_width;
    if (h.empty()) return 0;
    std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
    return h[h.size() / 2];
  }
};

constexpr ms::Estimator kEstimators[] = {ms::Estimator::kMean, ms::Estimator::kHuber};

ms::Settings settings_for(ms::Estimator estimator, bool adjust) {
  ms::Settings s;
  s.estimator = estimator;
  s.adjust_for_probe = adjust;
  return s;
}

Tallies run_seeds(const ms::SpeedModel& model, const ms::Settings& settings, ms::OrderKind kind,
                  std::size_t seeds = kSeeds) {
  Tallies t;
  t.twin.true_change = 0;
  t.planted.true_change = kPlanted;
  for (std::size_t i = 0; i < seeds; ++i) {
    const std::uint64_t seed = 0xc0ffee + 104729ull * i;
    const ms::SyntheticRun run =
        ms::simulate_rounds(model, {0.3, 0.3, 0.3 * (1.0 + kPlanted)}, 30, 4, kind, seed, {1.0, 1.3, 0.8, 1.1});
    const ms::PairedResult twin = ms::analyze_pairs(ms::pairs_of(run, 1, 0), settings);
    const ms::PairedResult planted = ms::analyze_pairs(ms::pairs_of(run, 2, 0), settings);
    t.twin.add(twin, 0);
    t.planted.add(planted, kPlanted);
    t.variance_removed_sum += twin.variance_removed + planted.variance_removed;
    t.adjusted_used += twin.uses_adjusted + planted.uses_adjusted;
    t.half_width.push_back(0.5 * (twin.chosen().high - twin.chosen().low));
    t.half_width.push_back(0.5 * (planted.chosen().high - planted.chosen().low));
  }
  return t;
}

struct Band {
  double low, high;
  bool holds(double x) const { return low <= x && x <= high; }
};

// Nominal 95 % within about 3.5 standard errors at 1000 seeds.
constexpr Band kNominal{0.92, 0.975};

// A 30-round run lasts about 28 simulated seconds.
struct Scenario {
  std::string name;
  ms::SpeedModel model;
  Band mean_raw;   // the band for the raw interval's coverage with the mean
  Band huber_raw;  // ... and with Huber's M-estimate
  const Band& raw_band(ms::Estimator e) const { return e == ms::Estimator::kMean ? mean_raw : huber_raw; }
};

std::vector<Scenario> scenarios() {
  std::vector<Scenario> out;
  ms::SpeedModel drift;  // 1 % slower per second: 28 % over the run
  drift.drift_per_s = 0.01;
  ms::SpeedModel step;  // 35 % slower from mid-run on
  step.step_at_s = 14;
  step.step = 0.3;
  ms::SpeedModel burst;  // 65 % slower for 2 s
  burst.burst_at_s = 10;
  burst.burst_s = 2;
  burst.burst = 0.5;
  ms::SpeedModel wander;  // the VMs' fast wander: 15 % spread, 0.5 s time constant
  wander.wander_sd = 0.15;
  wander.wander_tau_s = 0.5;
  // A step or a burst edge lands inside one or two rounds and makes each an outlier of the size of the jump;
  // the mean's t interval is conservative on such heavy-tailed rounds (98.5 % measured over 10,000 seeds), so
  // its band for those two sits higher; the top still fails an interval that always covers. Huber's M-estimate
  // weighs the outlier rounds down and covers at about the nominal rate in all four (94.3-95.0 % over 10,000
  // seeds), with an interval about as wide as the mean's on the normal noise of the drift and the wander, and a
  // quarter (step) to a sixth (burst) as wide where the edges make outliers.
  out.push_back({"steady drift", drift, {0.925, 0.975}, kNominal});
  out.push_back({"step change", step, {0.97, 0.997}, kNominal});
  out.push_back({"burst", burst, {0.97, 0.997}, kNominal});
  out.push_back({"fast wander", wander, {0.925, 0.975}, kNominal});
  return out;
}

// The rounds of the real VMs: most within ~2 %, one run in ten hit by a change of speed inside it and off by
// up to 20-30 % (1.5 % run noise, 10 % of the runs with an extra 25 % log-noise), no drift and no wander.
ms::SpeedModel heavy_tailed() {
  ms::SpeedModel m;
  m.run_noise_sd = 0.015;
  m.outlier_rate = 0.1;
  m.outlier_sd = 0.25;
  m.wander_sd = 0;
  return m;
}

ms::PairedResult made_result(ms::Decision decision, double low, double high) {
  ms::PairedResult r;
  r.decision = decision;
  r.raw.valid = decision != ms::Decision::kTooFewRounds;
  r.raw.low = low;
  r.raw.high = high;
  r.raw.estimate = 0.5 * (low + high);
  return r;
}

}  // namespace

TEST_CASE("CalibrationTally counts verdicts, coverage and findings of hand-made results", "[calibration]") {
  // An A/A pair: the truth is 0.
  ms::CalibrationTally aa;
  aa.add(made_result(ms::Decision::kEquivalent, -0.01, 0.012), 0);     // covers 0
  aa.add(made_result(ms::Decision::kSlower, 0.03, 0.05), 0);           // misses 0 above: a false difference
  aa.add(made_result(ms::Decision::kInconclusive, -0.04, -0.001), 0);  // misses 0 below
  aa.add(made_result(ms::Decision::kTooFewRounds, 0, 0), 0);           // counted as an experiment only
  CHECK(aa.experiments == 4);
  CHECK(aa.equivalent == 1);
  CHECK(aa.slower == 1);
  CHECK(aa.inconclusive == 1);
  CHECK(aa.too_few == 1);
  CHECK(aa.faster == 0);
  CHECK(aa.covered == 1);
  CHECK(aa.found == 0);  // nothing to find in an A/A pair
  CHECK(aa.false_diff == 2);
  CHECK(aa.false_verdicts() == 1);  // the slower verdict
  CHECK(aa.right_verdicts() == 1);  // equivalent
  CHECK(aa.rate(aa.covered) == Approx(0.25));
  // The mean change leaves the too-few experiment out: mean of exp(0.001), exp(0.04), exp(-0.0205), minus 1.
  const double mean_pct = 100.0 * ((std::exp(0.001) - 1.0) + (std::exp(0.04) - 1.0) + (std::exp(-0.0205) - 1.0)) / 3.0;
  CHECK(aa.mean_effect_pct() == Approx(mean_pct).epsilon(1e-12));

  // A planted 5 % slowdown: the truth is log 1.05 = 0.0488.
  ms::CalibrationTally slow;
  slow.true_change = kPlanted;
  slow.add(made_result(ms::Decision::kSlower, 0.03, 0.07), kPlanted);         // found and covered
  slow.add(made_result(ms::Decision::kInconclusive, 0.005, 0.04), kPlanted);  // found, not covered
  slow.add(made_result(ms::Decision::kInconclusive, -0.01, 0.06), kPlanted);  // covered, not found
  slow.add(made_result(ms::Decision::kFaster, -0.08, -0.03), kPlanted);       // the wrong side
  CHECK(slow.found == 2);
  CHECK(slow.covered == 2);
  CHECK(slow.false_diff == 1);
  CHECK(slow.false_verdicts() == 1);  // faster
  CHECK(slow.right_verdicts() == 1);  // slower

  // A planted speed-up mirrors it.
  ms::CalibrationTally fast;
  fast.true_change = -kPlanted;
  fast.add(made_result(ms::Decision::kFaster, -0.07, -0.03), -kPlanted);
  fast.add(made_result(ms::Decision::kSlower, 0.03, 0.07), -kPlanted);
  CHECK(fast.found == 1);
  CHECK(fast.covered == 1);
  CHECK(fast.false_diff == 1);
  CHECK(fast.false_verdicts() == 1);
  CHECK(fast.right_verdicts() == 1);

  // The tally reads the interval the verdict came from.
  ms::PairedResult adjusted = made_result(ms::Decision::kEquivalent, 0.03, 0.05);  // raw misses 0
  adjusted.adjusted.valid = true;
  adjusted.adjusted.low = -0.01;
  adjusted.adjusted.high = 0.01;
  adjusted.uses_adjusted = true;
  ms::CalibrationTally chosen;
  chosen.add(adjusted, 0);
  CHECK(chosen.covered == 1);
  CHECK(chosen.false_diff == 0);
  CHECK(ms::CalibrationTally{}.rate(0) == 0.0);
}

TEST_CASE("the raw 95 percent t interval covers the truth on drifting, stepping, bursting and wandering machines",
          "[coverage]") {
  for (const Scenario& s : scenarios()) {
    double half_width[2] = {};
    for (ms::Estimator e : kEstimators) {
      const Tallies t = run_seeds(s.model, settings_for(e, false), ms::OrderKind::kRandom);
      const double twin_cov = t.twin.rate(t.twin.covered), planted_cov = t.planted.rate(t.planted.covered);
      const double aa_false = t.twin.rate(t.twin.false_verdicts());
      half_width[e == ms::Estimator::kHuber] = t.median_half_width();
      WARN(s.name << " (raw, " << ms::to_string(e) << ", " << kSeeds << " seeds): coverage twin " << twin_cov
                  << ", planted " << planted_cov << "; A/A false verdicts " << aa_false
                  << ", A/A intervals excluding 0 " << t.twin.rate(t.twin.false_diff) << "; planted found "
                  << t.planted.rate(t.planted.found) << ", called slower " << t.planted.rate(t.planted.slower)
                  << ", mean effect " << t.planted.mean_effect_pct() << " %; median half-width "
                  << t.median_half_width());
      INFO(s.name << ", " << ms::to_string(e) << ": coverage twin " << twin_cov << ", planted " << planted_cov
                  << ", band [" << s.raw_band(e).low << ", " << s.raw_band(e).high << "]");
      CHECK(t.twin.too_few == 0);
      CHECK(t.adjusted_used == 0);
      CHECK(s.raw_band(e).holds(twin_cov));
      CHECK(s.raw_band(e).holds(planted_cov));
      CHECK(aa_false <= 0.05);
      CHECK(t.planted.rate(t.planted.false_verdicts()) == 0.0);  // a 5 % slowdown is never called faster
      // The estimate is unbiased: its mean over the seeds sits on the planted 5 %.
      CHECK(t.planted.mean_effect_pct() == Approx(100.0 * kPlanted).margin(0.5));
      CHECK(t.twin.mean_effect_pct() == Approx(0.0).margin(0.5));
    }
    // Huber's price on normal rounds is small (95 % efficiency): its interval is about as wide as the mean's.
    const double ratio = half_width[1] / half_width[0];
    INFO(s.name << ": median half-width, Huber / mean = " << ratio);
    if (s.name == "steady drift" || s.name == "fast wander") {
      CHECK(ratio > 0.95);
      CHECK(ratio < 1.1);
    } else {
      CHECK(ratio < 0.5);  // the step's and the burst's outlier rounds widen the mean's interval, not Huber's
    }
  }
}

TEST_CASE("on heavy-tailed rounds Huber's interval covers at the nominal rate and is far narrower than the mean's",
          "[coverage][huber]") {
  // Why Huber is the default: with one run in ten off by up to 20-30 %, the mean's interval is valid but
  // (conservative and) about three times as wide, so it misses a planted 5 % in a third of the runs.
  const ms::SpeedModel model = heavy_tailed();
  const Tallies mean = run_seeds(model, settings_for(ms::Estimator::kMean, false), ms::OrderKind::kRandom);
  const Tallies huber = run_seeds(model, settings_for(ms::Estimator::kHuber, false), ms::OrderKind::kRandom);
  const double ratio = huber.median_half_width() / mean.median_half_width();
  for (const Tallies* t : {&mean, &huber}) {
    const ms::Estimator e = t == &mean ? ms::Estimator::kMean : ms::Estimator::kHuber;
    WARN("heavy tails (raw, " << ms::to_string(e) << ", " << kSeeds << " seeds): coverage twin "
                              << t->twin.rate(t->twin.covered) << ", planted " << t->planted.rate(t->planted.covered)
                              << "; A/A false verdicts " << t->twin.rate(t->twin.false_verdicts()) << "; planted found "
                              << t->planted.rate(t->planted.found) << ", mean effect " << t->planted.mean_effect_pct()
                              << " %; median half-width " << t->median_half_width());
  }
  WARN("heavy tails: median half-width, Huber / mean = " << ratio);
  CHECK(kNominal.holds(huber.twin.rate(huber.twin.covered)));
  CHECK(kNominal.holds(huber.planted.rate(huber.planted.covered)));
  CHECK(ratio < 0.75);
  // Narrower and still centred: Huber finds the planted 5 % far more often, without false verdicts.
  CHECK(huber.planted.rate(huber.planted.found) > mean.planted.rate(mean.planted.found) + 0.2);
  CHECK(huber.planted.mean_effect_pct() == Approx(100.0 * kPlanted).margin(0.5));
  CHECK(huber.twin.rate(huber.twin.false_verdicts()) <= 0.05);
  CHECK(huber.planted.rate(huber.planted.false_verdicts()) == 0.0);
  // The mean's interval is valid here too, only conservative (97 % over 10,000 seeds).
  const Band mean_band{0.95, 0.99};
  CHECK(mean_band.holds(mean.twin.rate(mean.twin.covered)));
  CHECK(mean_band.holds(mean.planted.rate(mean.planted.covered)));
}

TEST_CASE("a fixed order under drift loses the coverage the random order keeps", "[coverage][negative-control]") {
  // The same drifting machine, arms always in the order A, twin, A x 1.05: the twin always runs 0.3 s after A
  // on a slower machine, so its interval is centred off 0. The coverage check above must be able to fail.
  ms::SpeedModel drift;
  drift.drift_per_s = 0.01;
  for (ms::Estimator e : kEstimators) {
    const Tallies fixed = run_seeds(drift, settings_for(e, false), ms::OrderKind::kFixed);
    const double twin_cov = fixed.twin.rate(fixed.twin.covered);
    const double planted_cov = fixed.planted.rate(fixed.planted.covered);
    WARN("steady drift, fixed order (raw, " << ms::to_string(e) << ", " << kSeeds << " seeds): coverage twin "
                                            << twin_cov << ", planted " << planted_cov << ", twin mean effect "
                                            << fixed.twin.mean_effect_pct() << " %, planted mean effect "
                                            << fixed.planted.mean_effect_pct() << " %");
    INFO(ms::to_string(e));
    CHECK(twin_cov < 0.85);
    CHECK(planted_cov < 0.85);
    CHECK(fixed.twin.mean_effect_pct() > 0.2);  // the later arm looks slower
  }
}

TEST_CASE("the probe-adjusted interval covers as well and removes the wander's variance", "[coverage]") {
  for (ms::Estimator e : kEstimators) {
    const ms::Settings adjusted = settings_for(e, true);  // the adjusted interval decides
    for (Scenario s : scenarios()) {
      s.model.probe_tracking = 1.0;
      s.model.probe_noise_sd = 0.001;
      const Tallies t = run_seeds(s.model, adjusted, ms::OrderKind::kRandom);
      const double twin_cov = t.twin.rate(t.twin.covered), planted_cov = t.planted.rate(t.planted.covered);
      WARN(s.name << " (adjusted, " << ms::to_string(e) << ", " << kSeeds << " seeds): coverage twin " << twin_cov
                  << ", planted " << planted_cov << "; A/A false verdicts " << t.twin.rate(t.twin.false_verdicts())
                  << "; planted found " << t.planted.rate(t.planted.found) << ", mean effect "
                  << t.planted.mean_effect_pct() << " %; mean variance removed " << t.mean_variance_removed());
      INFO(s.name << ", " << ms::to_string(e));
      CHECK(t.adjusted_used == 2 * kSeeds);
      // The probe sees the machine's slowness: the outlier rounds of a step or burst are explained away, so the
      // adjusted interval is near nominal in every scenario, for either estimator.
      const Band band = e == ms::Estimator::kMean ? Band{0.925, 0.975} : kNominal;
      CHECK(band.holds(twin_cov));
      CHECK(band.holds(planted_cov));
      CHECK(t.twin.rate(t.twin.false_verdicts()) <= 0.05);
      CHECK(t.planted.mean_effect_pct() == Approx(100.0 * kPlanted).margin(0.2));
      if (s.name == "fast wander") {
        CHECK(t.mean_variance_removed() > 0.3);
        CHECK(t.planted.rate(t.planted.found) > 0.95);  // the raw interval finds it in about a third of the seeds
      }
    }
  }
}

TEST_CASE("rounds that share an instance: the round-level interval undercovers, the cluster-robust one covers",
          "[coverage][instances][negative-control]") {
  // The main job's default run: 5 passes of 24 one-frame rounds (24 blocks); every arm's instance carries a
  // fixed offset of sd 2 % (the size the A/A twin showed between runs) on rounds with 1.5 % noise. Kept for the
  // whole run, no interval can include the offset; renewed every 6 rounds, the round-level interval still
  // takes 120 rounds as independent and undercovers; naming the instances makes it cluster-robust.
  ms::SpeedModel m;
  m.run_noise_sd = 0.015;
  m.instance_sd = 0.02;
  auto coverage = [&](std::size_t per_instance, bool name_instances, ms::Estimator e) {
    m.rounds_per_instance = per_instance;
    ms::CalibrationTally twin, planted;
    for (std::size_t i = 0; i < kSeeds; ++i) {
      const ms::SyntheticRun run = ms::simulate_rounds(m, {0.03, 0.03, 0.03 * (1.0 + kPlanted)}, 120, 24,
                                                       ms::OrderKind::kRandom, 0xfeed + 7919ull * i);
      for (auto [arm, tally, truth] : {std::tuple{1u, &twin, 0.0}, std::tuple{2u, &planted, kPlanted}}) {
        std::vector<ms::RoundPair> pairs = ms::pairs_of(run, arm, 0);
        if (!name_instances) {
          for (ms::RoundPair& p : pairs) p.candidate_instance = p.reference_instance = -1;
        }
        tally->add(ms::analyze_pairs(pairs, settings_for(e, false)), truth);
      }
    }
    return std::pair{twin.rate(twin.covered), planted.rate(planted.covered)};
  };
  for (ms::Estimator e : kEstimators) {
    const auto [run_twin, run_planted] = coverage(0, false, e);
    const auto [flat_twin, flat_planted] = coverage(6, false, e);
    const auto [cluster_twin, cluster_planted] = coverage(6, true, e);
    WARN("instance sd 2 %, " << ms::to_string(e) << ", " << kSeeds << " seeds: coverage with one instance per run "
                             << run_twin << " / " << run_planted << "; renewed every 6 rounds, round-level "
                             << flat_twin << " / " << flat_planted << ", cluster-robust " << cluster_twin << " / "
                             << cluster_planted << " (twin / planted)");
    INFO(ms::to_string(e));
    CHECK(run_twin < 0.5);
    CHECK(flat_twin < 0.85);
    CHECK(flat_planted < 0.85);
    CHECK(kNominal.holds(cluster_twin));
    CHECK(kNominal.holds(cluster_planted));
  }
}
