// paired_comparison_test.cpp — the bootstrap interval and the verdict on data whose answer is known.
#include "measure/paired_comparison.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace st = frontsteal::stats;

TEST_CASE("a clearly faster candidate is ahead, a clearly slower one behind", "[stats]") {
  const std::vector<double> reference = {100, 103, 98, 101, 99, 102, 100, 97, 104, 100};
  std::vector<double> faster, slower;
  for (double r : reference) {
    faster.push_back(0.8 * r);
    slower.push_back(1.25 * r);
  }
  faster[3] *= 1.05;  // not all pairs equal: the interval has width
  slower[6] *= 0.97;
  const st::Comparison a = st::compare_paired(faster, reference);
  CHECK(a.verdict == st::Verdict::kAhead);
  CHECK(a.ratio.high < 1.0);
  CHECK(a.effect_pct == Approx(-20.0).margin(0.5));
  const st::Comparison b = st::compare_paired(slower, reference);
  CHECK(b.verdict == st::Verdict::kBehind);
  CHECK(b.ratio.low > 1.0);
  CHECK(b.effect_pct == Approx(25.0).margin(0.5));
  CHECK(std::string(st::to_string(a.verdict)) == "ahead");
}

TEST_CASE("identical series, and noise that straddles 1, give no difference", "[stats]") {
  const std::vector<double> x = {40, 41, 39.5, 40.2, 42, 38.9, 40.1, 40.4, 39.8, 41.1};
  const st::Comparison same = st::compare_paired(x, x);
  CHECK(same.verdict == st::Verdict::kNoDifference);
  CHECK(same.ratio.median == 1.0);
  CHECK(same.effect_pct == 0.0);
  // Pairs above and below 1 in equal number: the interval must contain 1.
  std::vector<double> y = x;
  for (std::size_t i = 0; i < y.size(); ++i) y[i] *= (i % 2 ? 1.03 : 0.97);
  const st::Comparison mixed = st::compare_paired(y, x);
  CHECK(mixed.ratio.contains(1.0));
  CHECK(mixed.verdict == st::Verdict::kNoDifference);
}

TEST_CASE("five pairs: ahead only when every pair agrees", "[stats]") {
  // The bootstrap median of 5 values is the smallest with probability ~6 %, so the 2.5 % quantile is the
  // smallest ratio and the 97.5 % quantile the largest.
  const std::vector<double> ref = {10, 10, 10, 10, 10};
  const st::Comparison all = st::compare_paired({9.0, 9.5, 9.2, 9.8, 9.1}, ref);
  CHECK(all.verdict == st::Verdict::kAhead);
  CHECK(all.ratio.low == Approx(0.90));
  CHECK(all.ratio.high == Approx(0.98));
  const st::Comparison one_off = st::compare_paired({9.0, 9.5, 9.2, 10.2, 9.1}, ref);
  CHECK(one_off.verdict == st::Verdict::kNoDifference);
}

TEST_CASE("fewer than three pairs give no verdict", "[stats]") {
  CHECK(st::compare_paired({1.0, 1.0}, {2.0, 2.0}).verdict == st::Verdict::kTooFewRepeats);
  CHECK(st::compare_paired({}, {}).pairs == 0);
}

TEST_CASE("the same data and seed give the same interval, and the interval is ordered", "[stats]") {
  const std::vector<double> x = {1.02, 0.97, 1.10, 0.99, 1.05, 0.93, 1.01};
  const st::Interval a = st::bootstrap_median_ci(x);
  const st::Interval b = st::bootstrap_median_ci(x);
  CHECK(a.low == b.low);
  CHECK(a.high == b.high);
  CHECK(a.low <= a.median);
  CHECK(a.median <= a.high);
  CHECK(a.median == 1.01);
}

TEST_CASE("the 95 % interval covers the true median of a known distribution about 95 % of the time", "[stats]") {
  // Log-normal samples (median exactly 1, skewed like timings) of 15 values, 400 trials, fixed seed. The
  // percentile bootstrap of a median is a little conservative at small n (the interval ends fall on order
  // statistics); coverage well under 90 % or at 100 % would mean a wrong quantile or index.
  std::mt19937_64 gen(17);
  std::normal_distribution<double> normal(0.0, 0.1);
  int covered = 0;
  constexpr int kTrials = 400;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<double> x(15);
    for (double& v : x) v = std::exp(normal(gen));
    const st::Interval ci = st::bootstrap_median_ci(x, 0.95, 2000, st::kBootstrapSeed + t);
    if (ci.contains(1.0)) ++covered;
  }
  INFO("covered " << covered << " of " << kTrials);
  CHECK(covered >= static_cast<int>(0.90 * kTrials));
  CHECK(covered < kTrials);
}

TEST_CASE("splitmix64 indices cover the range evenly", "[stats]") {
  st::SplitMix64 rng(1);
  std::vector<int> counts(7, 0);
  for (int i = 0; i < 70000; ++i) ++counts[rng.index(7)];
  for (int c : counts) CHECK(std::abs(c - 10000) < 500);
}
