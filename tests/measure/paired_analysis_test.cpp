// paired_analysis_test.cpp — the log-ratio t interval, blocks, the probe covariate and the margin verdicts on
// hand-made rounds whose answers are known. Tests that check least-squares numbers (the mean, its sd, the t
// interval, the covariate's standard error, the rounds-needed formula) set Estimator::kMean explicitly; Huber's
// M-estimate (the default) has a hand-checked case of its own, and the verdict-only tests run both estimators.
#include "measure/paired_analysis.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "measure/student_t.hpp"

namespace ms = frontsteal::measure;

namespace {

// Jitter on the log scale that sums to exactly 0 over every two rounds (+a, -a with a varying), so the mean
// log-ratio is the planted one and the spread is known: rms(jitter) = amplitude * rms(kShape).
constexpr double kShape[] = {1.0, 0.4, 1.6, 0.7, 1.3};
double jitter(std::size_t round, double amplitude) {
  const double a = amplitude * kShape[(round / 2) % 5];
  return round % 2 == 0 ? a : -a;
}

// Rounds whose candidate / reference ratio is exp(log_ratio[r]); the reference time varies round to round (the
// analysis must use only the ratio).
std::vector<ms::RoundPair> pairs_with(const std::vector<double>& log_ratio, const std::vector<int>& block = {}) {
  std::vector<ms::RoundPair> out;
  for (std::size_t r = 0; r < log_ratio.size(); ++r) {
    ms::RoundPair p;
    p.reference = 2.0 + 0.37 * static_cast<double>(r % 7);
    p.candidate = p.reference * std::exp(log_ratio[r]);
    p.block = block.empty() ? 0 : block[r];
    out.push_back(p);
  }
  return out;
}

// The least-squares analysis (the mean and its t interval), for the tests whose numbers are worked by hand.
ms::Settings mean_settings() {
  ms::Settings s;
  s.estimator = ms::Estimator::kMean;
  return s;
}

ms::Settings settings_with(ms::Estimator estimator) {
  ms::Settings s;
  s.estimator = estimator;
  return s;
}

constexpr ms::Estimator kEstimators[] = {ms::Estimator::kMean, ms::Estimator::kHuber};

// `rounds` rounds at a constant ratio with relative jitter of about `amplitude`.
std::vector<ms::RoundPair> constant_ratio(double ratio, double amplitude, std::size_t rounds) {
  std::vector<double> d;
  for (std::size_t r = 0; r < rounds; ++r) d.push_back(std::log(ratio) + jitter(r, amplitude));
  return pairs_with(d);
}

}  // namespace

TEST_CASE("a constant ratio of 1.10 is slower, and 0.90 faster", "[paired_analysis]") {
  const ms::Settings mean = mean_settings();  // the jitter sums to 0: the mean is exactly the planted ratio
  const ms::PairedResult slow = ms::analyze_pairs(constant_ratio(1.10, 0.005, 10), mean);
  INFO(ms::describe(slow));
  CHECK(slow.rounds == 10);
  CHECK(slow.blocks == 1);
  CHECK(slow.decision == ms::Decision::kSlower);
  CHECK(slow.differs);
  CHECK_FALSE(slow.uses_adjusted);  // no probe measured
  CHECK(slow.raw.estimate == Approx(std::log(1.10)).margin(1e-12));
  CHECK(slow.raw.contains(std::log(1.10)));
  CHECK(slow.raw.low > std::log1p(0.02));
  CHECK(slow.raw.ratio() == Approx(1.10).epsilon(1e-12));
  CHECK(slow.raw.effect_pct() == Approx(10.0).margin(1e-9));
  CHECK(slow.rounds_needed == 0);
  CHECK(std::string(ms::to_string(slow.decision)) == "slower");

  const ms::PairedResult fast = ms::analyze_pairs(constant_ratio(0.90, 0.005, 10), mean);
  INFO(ms::describe(fast));
  CHECK(fast.decision == ms::Decision::kFaster);
  CHECK(fast.differs);
  CHECK(fast.raw.estimate == Approx(std::log(0.90)).margin(1e-12));
  CHECK(fast.raw.contains(std::log(0.90)));
  CHECK(fast.raw.high < -std::log1p(0.02));
  CHECK(std::string(ms::to_string(fast.decision)) == "faster");
  CHECK(ms::describe(fast).rfind("faster -10.0 %", 0) == 0);

  // Swapping the arms swaps the verdict: the candidate is the numerator.
  std::vector<ms::RoundPair> swapped = constant_ratio(1.10, 0.005, 10);
  for (ms::RoundPair& p : swapped) std::swap(p.candidate, p.reference);
  // The verdicts do not depend on the estimator.
  for (ms::Estimator e : kEstimators) {
    INFO(ms::to_string(e));
    CHECK(ms::analyze_pairs(constant_ratio(1.10, 0.005, 10), settings_with(e)).decision == ms::Decision::kSlower);
    CHECK(ms::analyze_pairs(constant_ratio(0.90, 0.005, 10), settings_with(e)).decision == ms::Decision::kFaster);
    CHECK(ms::analyze_pairs(swapped, settings_with(e)).decision == ms::Decision::kFaster);
  }
}

TEST_CASE("a ratio of 1.000 with 0.2 percent jitter over 20 rounds is equivalent within 2 percent",
          "[paired_analysis]") {
  for (ms::Estimator e : kEstimators) {
    const ms::PairedResult r = ms::analyze_pairs(constant_ratio(1.000, 0.002, 20), settings_with(e));
    INFO(ms::to_string(e) << ": " << ms::describe(r));
    CHECK(r.decision == ms::Decision::kEquivalent);
    CHECK_FALSE(r.differs);
    CHECK(r.raw.contains(0.0));
    CHECK(r.raw.low > -std::log1p(0.02));
    CHECK(r.raw.high < std::log1p(0.02));
    CHECK(r.margin == 0.02);
    CHECK(std::string(ms::to_string(r.decision)) == "equivalent");
    // Negative control: a margin narrower than the interval's half-width cannot call it equivalent.
    ms::Settings tight = settings_with(e);
    tight.margin = 0.0005;
    CHECK(ms::analyze_pairs(constant_ratio(1.000, 0.002, 20), tight).decision == ms::Decision::kInconclusive);
  }
}

TEST_CASE("noise too large for the rounds run is inconclusive, with more rounds needed", "[paired_analysis]") {
  const ms::Settings mean = mean_settings();  // the rounds-needed formula below is checked on the t interval's sd
  // 1.02 with 3 percent jitter over 6 rounds: the interval straddles the margin.
  const ms::PairedResult on_margin = ms::analyze_pairs(constant_ratio(1.02, 0.03, 6), mean);
  INFO(ms::describe(on_margin));
  CHECK(on_margin.decision == ms::Decision::kInconclusive);
  CHECK(on_margin.rounds_needed > 6);
  CHECK(std::string(ms::to_string(on_margin.decision)) == "inconclusive");

  // 1.03: the estimate lies about 1 percent past the margin, so the rounds needed are finite and follow
  // n = (z sd / gap)^2 + blocks, with z the normal 97.5 percent quantile.
  const ms::PairedResult past = ms::analyze_pairs(constant_ratio(1.03, 0.03, 6), mean);
  INFO(ms::describe(past));
  CHECK(past.decision == ms::Decision::kInconclusive);
  const double gap = std::log(1.03) - std::log1p(0.02);
  const double expected = std::ceil(std::pow(1.959964 * past.raw.sd / gap, 2.0)) + 1.0;
  CHECK(std::isfinite(past.rounds_needed));
  CHECK(past.rounds_needed == Approx(expected).margin(1.0));
  CHECK(past.rounds_needed > 6);
  // The rounds asked for do decide: the same series run that long is called slower.
  const auto enough = static_cast<std::size_t>(past.rounds_needed) + 4;
  CHECK(ms::analyze_pairs(constant_ratio(1.03, 0.03, enough), mean).decision == ms::Decision::kSlower);
}

TEST_CASE("four rounds in one block: estimate, sd and the t interval with df = 3 by hand", "[paired_analysis]") {
  // d = {0.01, 0.03, 0.02, 0.06}: mean 0.03, deviations {-0.02, 0, -0.01, 0.03}, sum of squares 0.0014.
  const ms::PairedResult r = ms::analyze_pairs(pairs_with({0.01, 0.03, 0.02, 0.06}), mean_settings());
  const double mean = 0.03;
  const double sd = std::sqrt(0.0014 / 3.0);  // n - 1 denominator
  const double se = sd / 2.0;                 // sd / sqrt(4)
  const double t3 = 3.1824;                   // t table, df = 3, p = .975
  INFO(ms::describe(r));
  CHECK(r.rounds == 4);
  CHECK(r.raw.valid);
  CHECK(r.raw.df == 3.0);
  CHECK(r.raw.estimate == Approx(mean).margin(1e-12));
  CHECK(r.raw.sd == Approx(sd).epsilon(1e-9));
  CHECK(r.raw.se == Approx(se).epsilon(1e-9));
  CHECK(r.raw.low == Approx(mean - t3 * se).margin(1e-5));
  CHECK(r.raw.high == Approx(mean + t3 * se).margin(1e-5));
  // The normal quantile would give a visibly narrower interval: the hand values tell them apart.
  CHECK(r.raw.high - r.raw.low > 2.0 * 1.96 * se + 0.01);
  CHECK(r.decision == ms::Decision::kInconclusive);  // low < 0 < margin < high
  CHECK_FALSE(r.differs);
  // The smallest change found with 80 percent power: (t_.975 + t_.80) at df = 3, times se.
  const double power_t = ms::student_t_quantile(0.975, 3) + ms::student_t_quantile(0.80, 3);
  CHECK(r.mde_pct == Approx(100.0 * (std::exp(power_t * se) - 1.0)).epsilon(1e-9));
  // A higher confidence widens the interval.
  ms::Settings s99 = mean_settings();
  s99.confidence = 0.99;
  const ms::PairedResult r99 = ms::analyze_pairs(pairs_with({0.01, 0.03, 0.02, 0.06}), s99);
  CHECK(r99.raw.high - r99.raw.low == Approx(2.0 * 5.8409 * se).epsilon(1e-4));
  // No round lies beyond k s from the centre (scale 1.4826 * 0.02 * sqrt(4/3) = 0.034, k s = 0.046 > 0.03): every
  // Huber weight is 1, so the M-estimate is the mean and its sandwich sd the t interval's.
  const ms::PairedResult huber =
      ms::analyze_pairs(pairs_with({0.01, 0.03, 0.02, 0.06}), settings_with(ms::Estimator::kHuber));
  CHECK(huber.raw.estimate == Approx(mean).margin(1e-12));
  CHECK(huber.raw.sd == Approx(sd).epsilon(1e-9));
  CHECK(huber.raw.low == Approx(r.raw.low).margin(1e-12));
  CHECK(huber.raw.high == Approx(r.raw.high).margin(1e-12));
}

TEST_CASE("one round far off: Huber's M-estimate stays with the other eight, the mean follows it",
          "[paired_analysis][huber]") {
  // 9 rounds in 1 block: eight at 0 with jitter +-a (a = 0.001, alternating), one at 0.5 (65 % slower, a round
  // the machine changed speed in).
  constexpr double a = 0.001;
  std::vector<double> d;
  for (std::size_t r = 0; r < 8; ++r) d.push_back(r % 2 == 0 ? a : -a);
  d.push_back(0.5);
  const ms::PairedResult mean = ms::analyze_pairs(pairs_with(d), mean_settings());
  const ms::PairedResult huber = ms::analyze_pairs(pairs_with(d), settings_with(ms::Estimator::kHuber));
  INFO("mean: " << ms::describe(mean) << "  Huber: " << ms::describe(huber) << " (estimate " << huber.raw.estimate
                << ", sd " << huber.raw.sd << ")");
  // The mean: 0.5 / 9, sd ~ 0.167, the interval [-0.073, 0.184] straddles both margins.
  CHECK(mean.raw.estimate == Approx(0.5 / 9.0).margin(1e-12));
  CHECK(mean.decision == ms::Decision::kInconclusive);
  // Huber, by hand. At the solution mu the eight residuals are a - mu (4) and -(a + mu) (4), the far round's
  // 0.5 - mu; the scale is the residuals' normalized MAD (the 5th smallest |e| of 9, a + mu) with the df
  // correction: s = 1.4826 sqrt(9/8) (a + mu). The far round gets psi = k and the eight psi = e / s, so
  // sum psi = 0 gives 8 mu / s = k: mu = c (a + mu), c = 1.345 * 1.4826 sqrt(9/8) / 8 = 0.264, mu = c a / (1 - c).
  const double k = 1.345, c = k * 1.4826 * std::sqrt(9.0 / 8.0) / 8.0;
  const double mu = c * a / (1.0 - c);  // 0.36 a
  const double s = 1.4826 * std::sqrt(9.0 / 8.0) * (a + mu);
  CHECK(a + mu < k * s);  // the eight are inside k s, the far round is not
  CHECK(huber.raw.estimate == Approx(mu).margin(1e-9));
  CHECK(std::fabs(huber.raw.estimate) < 0.01);
  // The sandwich: sd = K s sqrt(sum psi^2 / df) / mean psi', sum psi^2 = 8 (a^2 + mu^2) / s^2 + k^2, mean psi'
  // = 8/9, K = 1 + (p/n) var(psi') / mean(psi')^2 = 1 + (1/9)(1/8) = 73/72; se = sd / 3, df = 8.
  const double psi2 = 8.0 * (a * a + mu * mu) / (s * s) + k * k;
  const double sd = (73.0 / 72.0) * s * std::sqrt(psi2 / 8.0) / (8.0 / 9.0);
  CHECK(huber.raw.df == 8.0);
  CHECK(huber.raw.sd == Approx(sd).epsilon(1e-6));
  CHECK(huber.raw.se == Approx(sd / 3.0).epsilon(1e-6));
  const double t8 = ms::student_t_quantile(0.975, 8);
  CHECK(huber.raw.low == Approx(mu - t8 * sd / 3.0).margin(1e-8));
  CHECK(huber.raw.high == Approx(mu + t8 * sd / 3.0).margin(1e-8));
  // So the interval is a hundredth of the mean's (half-width 0.0013 against 0.128), and decides: equivalent.
  CHECK(huber.raw.high - huber.raw.low < 0.02 * (mean.raw.high - mean.raw.low));
  CHECK(huber.raw.contains(0.0));
  CHECK(huber.decision == ms::Decision::kEquivalent);
  // Huber's M-estimate is the default.
  CHECK(ms::Settings{}.estimator == ms::Estimator::kHuber);
  CHECK(ms::analyze_pairs(pairs_with(d)).raw.estimate == huber.raw.estimate);
  CHECK(std::string(ms::to_string(ms::Estimator::kHuber)) == "Huber M-estimate");
  CHECK(std::string(ms::to_string(ms::Estimator::kMean)) == "mean");
}

TEST_CASE("blocks remove their offsets from the spread but not from the estimate", "[paired_analysis]") {
  // Block 0 runs at 1.05, block 1 at 1.15, each with 0.2 percent jitter, five rounds each, interleaved.
  std::vector<double> d;
  std::vector<int> block;
  for (std::size_t r = 0; r < 10; ++r) {
    const int b = static_cast<int>(r % 2);
    block.push_back(b);
    d.push_back(std::log(b == 0 ? 1.05 : 1.15) + jitter(r / 2 + 5 * b, 0.002));
  }
  double mean = 0;
  for (double x : d) mean += x;
  mean /= static_cast<double>(d.size());
  const ms::Settings least_squares = mean_settings();  // the estimate is checked against the plain mean
  const ms::PairedResult r = ms::analyze_pairs(pairs_with(d, block), least_squares);
  INFO(ms::describe(r));
  CHECK(r.blocks == 2);
  CHECK(r.raw.df == 8.0);  // rounds - blocks
  CHECK(r.raw.estimate == Approx(mean).margin(1e-12));
  CHECK(r.raw.estimate == Approx(0.5 * (std::log(1.05) + std::log(1.15))).margin(1e-3));
  // Within-block spread ~0.002; the between-block spread (half of log(1.15/1.05) = 0.045) is not in it.
  CHECK(r.raw.sd < 0.004);
  CHECK(r.raw.sd > 0.001);

  // Negative control: the same rounds in one block carry the block offsets into the spread.
  const ms::PairedResult pooled = ms::analyze_pairs(pairs_with(d), least_squares);
  CHECK(pooled.blocks == 1);
  CHECK(pooled.raw.sd > 0.04);
  CHECK(pooled.raw.estimate == Approx(r.raw.estimate).margin(1e-12));

  // Unequal blocks: the estimate is the mean over every round, so a block's weight is its share of rounds.
  std::vector<double> d2;
  std::vector<int> block2;
  for (std::size_t r = 0; r < 9; ++r) {
    const int b = r < 3 ? 0 : 1;
    block2.push_back(b);
    d2.push_back(std::log(b == 0 ? 1.05 : 1.15));
  }
  d2[3] += 0.001;  // a little spread, so the interval has width
  d2[4] -= 0.001;
  const ms::PairedResult unequal = ms::analyze_pairs(pairs_with(d2, block2), least_squares);
  CHECK(unequal.raw.estimate == Approx((3.0 * std::log(1.05) + 6.0 * std::log(1.15)) / 9.0).margin(1e-12));
  CHECK(unequal.raw.df == 7.0);
}

namespace {

// The probe covariate's shape over 16 rounds, spread over +-0.12.
constexpr double kC[] = {0.10,  -0.08, 0.03,  -0.12, 0.06, -0.02, 0.12, -0.09,
                         -0.05, 0.09,  -0.11, 0.04,  0.07, -0.03, 0.01, -0.02};

double mean_of_kc() {
  double mean_c = 0;
  for (double c : kC) mean_c += c;
  return mean_c / 16.0;
}

// Rounds where d = 0.03 + c + noise, with c = log(candidate_probe / reference_probe) = kC minus its mean plus
// c_offset.
std::vector<ms::RoundPair> probed_rounds(double c_offset) {
  const double mean_c = mean_of_kc();
  std::vector<ms::RoundPair> out;
  for (std::size_t r = 0; r < 16; ++r) {
    const double c = kC[r] - mean_c + c_offset;
    ms::RoundPair p;
    p.reference = 3.0 + 0.1 * static_cast<double>(r);
    p.candidate = p.reference * std::exp(0.03 + c + jitter(r, 0.001));
    p.reference_probe = 1e6 * (1.0 + 0.05 * static_cast<double>(r % 3));  // only the probe's ratio matters
    p.candidate_probe = p.reference_probe * std::exp(c);
    out.push_back(p);
  }
  return out;
}

}  // namespace

TEST_CASE("the probe covariate narrows the interval and recovers the slope", "[paired_analysis]") {
  const ms::PairedResult r = ms::analyze_pairs(probed_rounds(0.0), mean_settings());
  INFO(ms::describe(r) << "  raw sd " << r.raw.sd << "  adjusted sd " << r.adjusted.sd << "  slope " << r.probe_slope
                       << "  variance removed " << r.variance_removed);
  REQUIRE(r.adjusted.valid);
  CHECK(r.uses_adjusted);
  CHECK(r.adjusted.df == 14.0);  // rounds - blocks - 1
  CHECK(r.probe_slope == Approx(1.0).margin(0.02));
  CHECK(r.variance_removed > 0.9);
  CHECK(r.adjusted.high - r.adjusted.low < 0.1 * (r.raw.high - r.raw.low));
  CHECK(r.adjusted.estimate == Approx(0.03).margin(0.001));
  CHECK(r.adjusted.ratio() == Approx(std::exp(0.03)).epsilon(1e-3));
  CHECK(r.adjusted.contains(0.03));
  CHECK(r.raw.estimate == Approx(0.03).margin(1e-12));  // mean(c) = 0 and the jitter sums to 0
  // The adjusted interval decides (slower, 3 percent past a 2 percent margin); the raw one cannot.
  CHECK(r.decision == ms::Decision::kSlower);

  // Without the adjustment the same rounds are decided from the raw interval, whose spread is the probe's.
  ms::Settings raw_only = mean_settings();
  raw_only.adjust_for_probe = false;
  const ms::PairedResult plain = ms::analyze_pairs(probed_rounds(0.0), raw_only);
  CHECK_FALSE(plain.uses_adjusted);
  CHECK(plain.adjusted.valid);  // still reported
  CHECK(plain.decision == ms::Decision::kInconclusive);
  CHECK(&plain.chosen() == &plain.raw);
  CHECK(plain.raw.sd > 0.05);
}

TEST_CASE("the adjustment removes slope times the covariate's mean", "[paired_analysis]") {
  // The probe says the candidate ran on a 5 percent slower machine on average: the raw estimate carries it,
  // the adjusted one does not.
  const ms::PairedResult r = ms::analyze_pairs(probed_rounds(0.05), mean_settings());
  REQUIRE(r.adjusted.valid);
  CHECK(r.raw.estimate == Approx(0.08).margin(1e-9));
  CHECK(r.adjusted.estimate == Approx(0.03).margin(0.001));
  CHECK(r.probe_slope == Approx(1.0).margin(0.02));
  // The adjusted estimate's standard error carries the uncertainty of the slope times the covariate's mean:
  // se = sd * sqrt(1/N + mean(c)^2 / Sxx).
  double sxx = 0;
  for (double c : kC) sxx += (c - mean_of_kc()) * (c - mean_of_kc());
  CHECK(r.adjusted.se == Approx(r.adjusted.sd * std::sqrt(1.0 / 16.0 + 0.05 * 0.05 / sxx)).epsilon(1e-9));
  CHECK(r.adjusted.se > 1.1 * r.adjusted.sd / 4.0);  // visibly above sd / sqrt(N)
}

TEST_CASE("a round without a probe leaves the adjusted interval out", "[paired_analysis]") {
  for (ms::Estimator e : kEstimators) {
    INFO(ms::to_string(e));
    const ms::Settings settings = settings_with(e);
    std::vector<ms::RoundPair> pairs = probed_rounds(0.0);
    pairs[5].candidate_probe = 0;
    const ms::PairedResult r = ms::analyze_pairs(pairs, settings);
    CHECK_FALSE(r.adjusted.valid);
    CHECK_FALSE(r.uses_adjusted);
    CHECK(r.raw.valid);
    CHECK(r.variance_removed == 0.0);
    CHECK(r.decision == ms::Decision::kInconclusive);  // from the raw interval
    pairs = probed_rounds(0.0);
    pairs[0].reference_probe = 0;
    CHECK_FALSE(ms::analyze_pairs(pairs, settings).adjusted.valid);
    // A probe that does not vary carries no information either.
    pairs = probed_rounds(0.0);
    for (ms::RoundPair& p : pairs) p.candidate_probe = p.reference_probe;
    CHECK_FALSE(ms::analyze_pairs(pairs, settings).adjusted.valid);
  }
}

TEST_CASE("too few rounds give no interval and no verdict", "[paired_analysis]") {
  for (ms::Estimator e : kEstimators) {
    INFO(ms::to_string(e));
    const ms::Settings settings = settings_with(e);
    const ms::PairedResult two = ms::analyze_pairs(pairs_with({0.1, 0.12}), settings);
    CHECK(two.rounds == 2);
    CHECK(two.decision == ms::Decision::kTooFewRounds);
    CHECK_FALSE(two.raw.valid);
    CHECK_FALSE(two.differs);
    CHECK(std::string(ms::to_string(two.decision)) == "too few rounds");
    CHECK(ms::describe(two) == "too few rounds");
    CHECK(ms::analyze_pairs({}, settings).decision == ms::Decision::kTooFewRounds);
    // Blocks take degrees of freedom: 4 rounds in 3 blocks are too few, 3 rounds in 1 block are enough.
    CHECK(ms::analyze_pairs(pairs_with({0.1, 0.12, 0.11, 0.13}, {0, 1, 2, 2}), settings).decision ==
          ms::Decision::kTooFewRounds);
    const ms::PairedResult three = ms::analyze_pairs(pairs_with({0.1, 0.12, 0.11}), settings);
    CHECK(three.raw.valid);
    CHECK(three.raw.df == 2.0);
    // A pair with a non-positive time is left out, which can leave too few.
    std::vector<ms::RoundPair> holed = pairs_with({0.1, 0.12, 0.11});
    holed[1].candidate = 0;
    const ms::PairedResult left = ms::analyze_pairs(holed, settings);
    CHECK(left.rounds == 2);
    CHECK(left.decision == ms::Decision::kTooFewRounds);
  }
}

// Rounds that name the instances that ran them: `per` consecutive rounds share one instance of each arm.
std::vector<ms::RoundPair> with_instances(std::vector<ms::RoundPair> pairs, std::size_t candidate_per,
                                          std::size_t reference_per) {
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    pairs[r].candidate_instance = static_cast<int>(r / candidate_per);
    pairs[r].reference_instance = static_cast<int>(r / reference_per);
  }
  return pairs;
}

TEST_CASE("a fresh instance every round gives exactly the round-level interval", "[paired_analysis][instances]") {
  std::vector<double> d;
  std::vector<int> block;
  for (std::size_t r = 0; r < 40; ++r) {
    d.push_back(0.01 + jitter(r, 0.02) + (r % 11 == 3 ? 0.2 : 0.0));  // a few outliers: Huber's weights in play
    block.push_back(static_cast<int>(r % 4));
  }
  for (ms::Estimator e : kEstimators) {
    INFO(ms::to_string(e));
    const ms::PairedResult plain = ms::analyze_pairs(pairs_with(d, block), settings_with(e));
    const ms::PairedResult named = ms::analyze_pairs(with_instances(pairs_with(d, block), 1, 1), settings_with(e));
    CHECK(plain.clusters == 40);
    CHECK(named.clusters == 40);
    CHECK(named.raw.estimate == Approx(plain.raw.estimate).margin(1e-15));
    CHECK(named.raw.se == Approx(plain.raw.se).epsilon(1e-12));
    CHECK(named.raw.df == plain.raw.df);
    CHECK(named.decision == plain.decision);
  }
}

TEST_CASE("rounds that share an instance: the cluster-robust standard error by hand", "[paired_analysis][instances]") {
  // One block, four instances of two rounds each, the mean: d = {0.01, 0.03 | -0.02, 0.00 | 0.05, 0.03 | -0.01,
  // -0.01}, mean 0.01; residuals summed per cluster {0.02, -0.04, 0.06, -0.04}, squares 0.0072; each round's
  // influence is its residual / N, so se^2 = 0.0072 / 64 * G / (G - 1) with G = 4, df = G - 1 = 3.
  const std::vector<double> d{0.01, 0.03, -0.02, 0.00, 0.05, 0.03, -0.01, -0.01};
  const ms::PairedResult r = ms::analyze_pairs(with_instances(pairs_with(d), 2, 2), mean_settings());
  const double se = std::sqrt(0.0072 / 64.0 * 4.0 / 3.0);
  CHECK(r.clusters == 4);
  CHECK(r.raw.estimate == Approx(0.01).margin(1e-12));
  CHECK(r.raw.df == 3.0);
  CHECK(r.raw.se == Approx(se).epsilon(1e-9));
  CHECK(r.raw.high - r.raw.low == Approx(2.0 * 3.1824 * se).epsilon(1e-4));
  // The same rounds taken as independent: 7 degrees of freedom and a narrower interval. The clusters' sums
  // disagree more than their rounds do, which only the cluster-robust error sees.
  const ms::PairedResult flat = ms::analyze_pairs(pairs_with(d), mean_settings());
  CHECK(flat.raw.df == 7.0);
  CHECK(flat.raw.se < r.raw.se);
}

TEST_CASE("instances of the two arms join rounds into clusters, and the blocks take their share of the cluster sums",
          "[paired_analysis][instances]") {
  std::vector<double> d;
  std::vector<int> block;
  for (std::size_t r = 0; r < 48; ++r) {
    d.push_back(jitter(r, 0.02));
    block.push_back(static_cast<int>(r % 12));  // 4 passes of 12 segments
  }
  // The candidate renewed every 12 rounds (per pass), the reference every 4: a cluster is a pass.
  const ms::PairedResult per_pass = ms::analyze_pairs(with_instances(pairs_with(d, block), 12, 4), mean_settings());
  CHECK(per_pass.clusters == 4);
  CHECK(per_pass.raw.df == 3.0);  // 4 clusters, all covering the same 12 blocks: one set
  // Both renewed every 4 rounds: 12 clusters covering 3 different sets of blocks, df = 12 - 3.
  const ms::PairedResult per_third = ms::analyze_pairs(with_instances(pairs_with(d, block), 4, 4), mean_settings());
  CHECK(per_third.clusters == 12);
  CHECK(per_third.raw.df == 9.0);
  // A random half of those rounds (as a resampled experiment draws them): clusters hold partial stretches, the
  // blocks take less from their sums, and the interval keeps most of its degrees of freedom.
  std::vector<ms::RoundPair> half;
  const std::vector<ms::RoundPair> all = with_instances(pairs_with(d, block), 4, 4);
  for (std::size_t r = 0; r < all.size(); ++r) {
    if ((r * 7 + 3) % 10 < 5) half.push_back(all[r]);
  }
  const ms::PairedResult sampled = ms::analyze_pairs(half, mean_settings());
  CHECK(sampled.raw.valid);
  CHECK(sampled.raw.df > 0.5 * static_cast<double>(sampled.clusters));
  CHECK(sampled.raw.df < static_cast<double>(sampled.clusters));
  // One instance for the whole run: one cluster, no interval at all (nothing tells the instance from the code).
  const ms::PairedResult one = ms::analyze_pairs(with_instances(pairs_with(d, block), 48, 48), mean_settings());
  CHECK(one.clusters == 1);
  CHECK_FALSE(one.raw.valid);
  CHECK(one.decision == ms::Decision::kTooFewRounds);
}

TEST_CASE("rounds_for_power follows the 80 percent power formula", "[paired_analysis]") {
  const double expected = 7.85 * std::pow(0.05 / std::log(1.02), 2.0) + 2.0;
  CHECK(ms::rounds_for_power(0.05, 0.02) == Approx(expected).epsilon(1e-12));
  CHECK(ms::rounds_for_power(0.05, 0.02) == Approx(52.05).margin(0.05));
  // Twice the spread, four times the rounds beyond the two a t interval needs anyway.
  CHECK(ms::rounds_for_power(0.10, 0.02) - 2.0 == Approx(4.0 * (expected - 2.0)).epsilon(1e-12));
  CHECK(std::isinf(ms::rounds_for_power(0.05, 0.0)));
}
