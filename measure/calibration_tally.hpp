// calibration_tally.hpp — how often a method gives each verdict when the truth is known: the A/A false-verdict
// rate, the detection rate of a planted change, and the coverage of the intervals.
//
// A method is trusted on a machine when, on that machine, it calls identical code equivalent (or at least
// never faster / slower) at about the nominal rate, and finds planted differences of known size (Kohavi et al.,
// DMKD 2009, A/A tests; Laaber, Scheuner & Leitner, EMSE 2019, planted slowdowns on cloud VMs). The same tally
// serves synthetic series (tests), the main job's built-in calibration arms (one experiment per run) and
// experiments resampled from long runs (subset_of_rounds).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "measure/paired_analysis.hpp"
#include "measure/paired_comparison.hpp"

namespace frontsteal::measure {

struct CalibrationTally {
  double true_change = 0;  // candidate / reference - 1 that was planted (0: an A/A pair)
  std::size_t experiments = 0, faster = 0, slower = 0, equivalent = 0, inconclusive = 0, too_few = 0;
  std::size_t found = 0;       // the interval excludes 0 on the planted change's side (never for A/A)
  std::size_t false_diff = 0;  // the interval excludes 0 on the other side (A/A: on either side)
  std::size_t covered = 0;     // the planted change lies inside the interval
  double effect_sum_pct = 0;   // sum of the estimated changes, for their mean

  void add(const PairedResult& r, double true_change_now) {
    ++experiments;
    switch (r.decision) {
      case Decision::kFaster: ++faster; break;
      case Decision::kSlower: ++slower; break;
      case Decision::kEquivalent: ++equivalent; break;
      case Decision::kInconclusive: ++inconclusive; break;
      case Decision::kTooFewRounds: ++too_few; return;
    }
    const LogInterval& li = r.chosen();
    const double truth = std::log1p(true_change_now);
    if (li.contains(truth)) ++covered;
    const bool above = li.low > 0, below = li.high < 0;
    if (truth > 0 ? above : truth < 0 ? below : false) ++found;
    if (truth > 0 ? below : truth < 0 ? above : (above || below)) ++false_diff;
    effect_sum_pct += li.effect_pct();
  }
  // The verdicts that contradict the truth: for A/A, faster or slower; for a slowdown, faster; for a speed-up,
  // slower.
  std::size_t false_verdicts() const { return true_change > 0 ? faster : true_change < 0 ? slower : faster + slower; }
  // The verdict the planted change should get beyond the margin (slower / faster; A/A: equivalent).
  std::size_t right_verdicts() const { return true_change > 0 ? slower : true_change < 0 ? faster : equivalent; }
  double rate(std::size_t count) const { return experiments ? static_cast<double>(count) / experiments : 0.0; }
  double mean_effect_pct() const {
    const std::size_t decided = experiments - too_few;
    return decided ? effect_sum_pct / static_cast<double>(decided) : 0.0;
  }
};

// Experiment `experiment` of a resampling: `n` distinct round indices out of `total`, drawn without
// replacement (the same draw for every comparison of that experiment).
inline std::vector<std::size_t> subset_of_rounds(std::size_t total, std::size_t n, std::uint64_t seed,
                                                 std::size_t experiment) {
  std::vector<std::size_t> idx(total);
  std::iota(idx.begin(), idx.end(), std::size_t{0});
  stats::SplitMix64 rng(seed ^ (0xd1b5'4a32'd192'ed03ull * (experiment + 1)));
  n = std::min(n, total);
  for (std::size_t i = 0; i < n; ++i) std::swap(idx[i], idx[i + rng.index(total - i)]);
  idx.resize(n);
  std::sort(idx.begin(), idx.end());
  return idx;
}

inline std::vector<RoundPair> select_rounds(const std::vector<RoundPair>& pairs, const std::vector<std::size_t>& idx) {
  std::vector<RoundPair> out;
  for (std::size_t i : idx) {
    if (i < pairs.size()) out.push_back(pairs[i]);
  }
  return out;
}

}  // namespace frontsteal::measure
