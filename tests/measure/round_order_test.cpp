// round_order_test.cpp — the orders of a round are permutations, the random one reproducible and balanced, and
// the fixed order's bias under a steady drift (the negative control) gone under the random one.
#include "measure/round_order.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "measure/synthetic_machine.hpp"

namespace ms = frontsteal::measure;

namespace {

bool is_permutation_of_arms(const std::vector<std::size_t>& order, std::size_t arms) {
  if (order.size() != arms) return false;
  std::vector<std::size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < arms; ++i) {
    if (sorted[i] != i) return false;
  }
  return true;
}

constexpr std::uint64_t kSeed = 0x0dde'c0de'5eed'0001ull;

}  // namespace

TEST_CASE("every order kind gives a permutation of the arms", "[round_order]") {
  for (ms::OrderKind kind : {ms::OrderKind::kRandom, ms::OrderKind::kCounterbalanced, ms::OrderKind::kFixed}) {
    for (std::size_t arms : {0, 1, 2, 3, 5, 8}) {
      for (std::size_t round = 0; round < 64; ++round) {
        INFO(ms::to_string(kind) << "  arms " << arms << "  round " << round);
        CHECK(is_permutation_of_arms(ms::round_order(arms, kSeed, round, kind), arms));
      }
    }
  }
}

TEST_CASE("order kinds round-trip through their names", "[round_order]") {
  for (ms::OrderKind kind : {ms::OrderKind::kRandom, ms::OrderKind::kCounterbalanced, ms::OrderKind::kFixed}) {
    CHECK(ms::order_kind_named(ms::to_string(kind)) == kind);
  }
  CHECK_FALSE(ms::order_kind_named("shuffled").has_value());
}

TEST_CASE("the fixed order is the identity, the counterbalanced one reverses odd rounds", "[round_order]") {
  const std::vector<std::size_t> identity = {0, 1, 2, 3};
  const std::vector<std::size_t> reversed = {3, 2, 1, 0};
  for (std::size_t round = 0; round < 10; ++round) {
    INFO("round " << round);
    CHECK(ms::round_order(4, kSeed, round, ms::OrderKind::kFixed) == identity);
    CHECK(ms::round_order(4, kSeed, round, ms::OrderKind::kCounterbalanced) == (round % 2 == 1 ? reversed : identity));
  }
}

TEST_CASE("the random order is reproducible for (seed, round) and changes across rounds and seeds", "[round_order]") {
  std::set<std::vector<std::size_t>> seen;
  std::size_t same_as_other_seed = 0;
  for (std::size_t round = 0; round < 40; ++round) {
    const auto a = ms::round_order(5, kSeed, round, ms::OrderKind::kRandom);
    INFO("round " << round);
    CHECK(a == ms::round_order(5, kSeed, round, ms::OrderKind::kRandom));  // recomputed on its own
    seen.insert(a);
    if (a == ms::round_order(5, kSeed + 1, round, ms::OrderKind::kRandom)) ++same_as_other_seed;
  }
  // 40 draws from 120 orders of 5 arms: ~34 distinct expected. A generator stuck on one order gives 1.
  CHECK(seen.size() >= 25);
  CHECK(same_as_other_seed <= 3);
  // Round k's order does not depend on which rounds were drawn before it.
  const auto late = ms::round_order(5, kSeed, 1000, ms::OrderKind::kRandom);
  for (std::size_t round = 0; round < 5; ++round) (void)ms::round_order(5, kSeed, round, ms::OrderKind::kRandom);
  CHECK(ms::round_order(5, kSeed, 1000, ms::OrderKind::kRandom) == late);
}

TEST_CASE("under the random order each arm takes each position about equally often", "[round_order]") {
  // 3 arms over 6000 rounds: 2000 expected per (arm, position) and 1000 per order. The bounds are loose
  // chi-square tails (4 and 5 degrees of freedom, p ~ 1e-5): they catch a biased shuffle (e.g. the naive
  // swap-with-any-index one, whose chi-square here is in the hundreds), not sampling noise.
  constexpr std::size_t kArms = 3, kRounds = 6000;
  std::size_t count[kArms][kArms] = {};
  std::map<std::vector<std::size_t>, std::size_t> orders;
  for (std::size_t round = 0; round < kRounds; ++round) {
    const auto order = ms::round_order(kArms, kSeed, round, ms::OrderKind::kRandom);
    for (std::size_t pos = 0; pos < kArms; ++pos) ++count[order[pos]][pos];
    ++orders[order];
  }
  double chi_positions = 0;
  const double expected = static_cast<double>(kRounds) / kArms;
  for (auto& row : count) {
    for (std::size_t c : row) chi_positions += std::pow(static_cast<double>(c) - expected, 2.0) / expected;
  }
  double chi_orders = 0;
  const double expected_order = static_cast<double>(kRounds) / 6.0;
  for (const auto& [order, c] : orders)
    chi_orders += std::pow(static_cast<double>(c) - expected_order, 2.0) / expected_order;
  INFO("chi-square of arm by position " << chi_positions << " (df 4), of the six orders " << chi_orders << " (df 5)");
  CHECK(orders.size() == 6);
  CHECK(chi_positions < 25.0);
  CHECK(chi_orders < 28.0);
  // Negative control: the fixed order puts arm 0 first every time.
  std::size_t first_fixed = 0;
  for (std::size_t round = 0; round < kRounds; ++round) {
    first_fixed += ms::round_order(kArms, kSeed, round, ms::OrderKind::kFixed)[0] == 0;
  }
  CHECK(first_fixed == kRounds);
}

namespace {

// A machine that only drifts (1 percent slower per second) and two identical arms of 0.3 s: any difference the
// analysis finds between them is the order's doing. The raw interval decides, so the probe plays no part; the
// estimator is explicit (the mean: the least-squares numbers documented below; Huber's M-estimate: the default).
struct AaUnderDrift {
  std::size_t seeds = 0, differs = 0, later_slower = 0;
  double mean_estimate = 0;
};

AaUnderDrift aa_under_drift(ms::OrderKind kind, std::size_t seeds, ms::Estimator estimator) {
  ms::SpeedModel model;
  model.drift_per_s = 0.01;
  model.run_noise_sd = 0.002;
  model.wander_sd = 0;
  ms::Settings raw;
  raw.adjust_for_probe = false;
  raw.estimator = estimator;
  AaUnderDrift out;
  for (std::size_t i = 0; i < seeds; ++i) {
    const ms::SyntheticRun run = ms::simulate_rounds(model, {0.3, 0.3}, 40, 1, kind, 0xa11ce + 7919 * i);
    const ms::PairedResult r = ms::analyze_pairs(ms::pairs_of(run, 1, 0), raw);
    ++out.seeds;
    out.differs += r.differs;
    out.later_slower += r.raw.low > 0;
    out.mean_estimate += r.raw.estimate;
  }
  out.mean_estimate /= static_cast<double>(seeds);
  return out;
}

}  // namespace

TEST_CASE("a fixed order under steady drift makes identical arms differ: the later one is slower",
          "[round_order][negative-control]") {
  // Arm 1 always starts ~0.3 s after arm 0, on a machine 0.3 percent slower: d ~ 0.01 * 0.3 * exp(s) per round,
  // against a run noise of 0.2 percent per arm. The bias is in every round, so either estimator sees it.
  for (ms::Estimator e : {ms::Estimator::kMean, ms::Estimator::kHuber}) {
    const AaUnderDrift fixed = aa_under_drift(ms::OrderKind::kFixed, 50, e);
    INFO(ms::to_string(e) << ", fixed order: " << fixed.differs << " of " << fixed.seeds << " A/A comparisons differ, "
                          << fixed.later_slower << " with the later arm slower, mean log-ratio "
                          << fixed.mean_estimate);
    CHECK(fixed.differs == fixed.seeds);
    CHECK(fixed.later_slower == fixed.seeds);
    CHECK(fixed.mean_estimate > 0.0028);
    CHECK(fixed.mean_estimate < 0.0042);
  }
}

TEST_CASE("the random order removes the drift's bias: identical arms differ at about the nominal rate",
          "[round_order]") {
  for (ms::Estimator e : {ms::Estimator::kMean, ms::Estimator::kHuber}) {
    const AaUnderDrift random = aa_under_drift(ms::OrderKind::kRandom, 200, e);
    const double rate = static_cast<double>(random.differs) / static_cast<double>(random.seeds);
    INFO(ms::to_string(e) << ", random order: " << random.differs << " of " << random.seeds
                          << " A/A comparisons differ (rate " << rate << "), mean log-ratio " << random.mean_estimate);
    CHECK(rate <= 0.08);
    CHECK(std::fabs(random.mean_estimate) < 0.0003);  // a tenth of the fixed order's bias
    // Counterbalancing cancels a linear drift over each pair of rounds.
    const AaUnderDrift balanced = aa_under_drift(ms::OrderKind::kCounterbalanced, 200, e);
    INFO("counterbalanced: " << balanced.differs << " differ, mean log-ratio " << balanced.mean_estimate);
    CHECK(static_cast<double>(balanced.differs) / static_cast<double>(balanced.seeds) <= 0.08);
    CHECK(std::fabs(balanced.mean_estimate) < 0.0003);
  }
}
