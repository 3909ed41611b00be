// paired_comparison.hpp — medians with percentile-bootstrap intervals, and a paired comparison of two series by
// the median of their per-repeat ratios: what frontsteal-mpi reports for its frame times and latencies, and what
// the installed example prints. The main job and frontsteal-paper decide their comparisons with
// paired_analysis.hpp instead (rounds in random order, a robust estimate, verdicts against a margin); the
// splitmix64 generator and quantile_sorted below serve both.
//
// Repeats are interleaved (repeat r of every scheduler runs in the same round as repeat r of the reference),
// so the slow drift of a shared machine hits both members of a pair alike: the per-repeat ratio
// candidate[r] / reference[r] cancels most of it, which the ratio of two medians does not. We report the
// median of those paired ratios with a percentile-bootstrap confidence interval of the median (Efron &
// Tibshirani, An Introduction to the Bootstrap, 1993, ch. 13): resample the ratios with replacement, take each
// resample's median, read the interval off the sorted medians. The median, not the mean, because one repeat
// hit by a burst of background work must not move the answer.
//
// Verdict, for times (lower is better): the whole interval below 1 → ahead; above 1 → behind; containing 1 →
// no difference. Effect size: (median ratio − 1) in %, the change in path time (negative = faster).
// With few repeats the interval is wide on purpose: with 5, "ahead" needs every pair to agree (the bootstrap
// median of 5 values falls on the smallest with probability ~6 %, above the 2.5 % tail).
//
// The generator is fixed (splitmix64 and a multiply-shift index, both spelled out here), so a given sample
// gives the same interval on every platform and standard library; std::uniform_int_distribution does not
// promise that.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "measure/machine_info.hpp"

namespace frontsteal::stats {

inline constexpr std::uint64_t kBootstrapSeed = 0x5eed'f00d'2024'0017ull;
inline constexpr int kBootstrapResamples = 10000;
inline constexpr std::size_t kMinPairsForVerdict = 3;  // below this a bootstrap interval means nothing

struct Interval {
  double median = 0, low = 0, high = 0;
  bool contains(double x) const noexcept { return low <= x && x <= high; }
};

enum class Verdict { kAhead, kBehind, kNoDifference, kTooFewRepeats };

inline const char* to_string(Verdict v) noexcept {
  switch (v) {
    case Verdict::kAhead: return "ahead";
    case Verdict::kBehind: return "behind";
    case Verdict::kNoDifference: return "no difference";
    case Verdict::kTooFewRepeats: return "too few repeats";
  }
  return "?";
}

// splitmix64 (Steele, Lea & Flood, OOPSLA 2014): small, fast, and every seed is a good one.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9e37'79b9'7f4a'7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58'476d'1ce4'e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d0'49bb'1331'11ebull;
    return z ^ (z >> 31);
  }
  // An index in [0, n): the high 32 bits scaled by n (Lemire's multiply-shift; the bias, < n / 2^32, is far
  // below anything a few dozen repeats can show).
  std::size_t index(std::size_t n) noexcept {
    return static_cast<std::size_t>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }

 private:
  std::uint64_t state_;
};

// The q-quantile (0 ≤ q ≤ 1) of sorted values, interpolated linearly between order statistics.
inline double quantile_sorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0;
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(pos));
  if (i + 1 >= sorted.size()) return sorted.back();
  const double frac = pos - static_cast<double>(i);
  return sorted[i] + frac * (sorted[i + 1] - sorted[i]);
}

// The median of x and its percentile-bootstrap confidence interval at `confidence` (e.g. 0.95).
inline Interval bootstrap_median_ci(const std::vector<double>& x, double confidence = 0.95,
                                    int resamples = kBootstrapResamples, std::uint64_t seed = kBootstrapSeed) {
  Interval out;
  out.median = median(x);
  if (x.size() < 2) {
    out.low = out.high = out.median;
    return out;
  }
  SplitMix64 rng(seed);
  std::vector<double> medians(static_cast<std::size_t>(resamples));
  std::vector<double> draw(x.size());
  for (double& m : medians) {
    for (double& d : draw) d = x[rng.index(x.size())];
    m = median(draw);
  }
  std::sort(medians.begin(), medians.end());
  const double tail = (1.0 - confidence) / 2;
  out.low = quantile_sorted(medians, tail);
  out.high = quantile_sorted(medians, 1.0 - tail);
  return out;
}

// candidate[r] / reference[r] for every repeat both have (the shorter length wins).
inline std::vector<double> paired_ratios(const std::vector<double>& candidate, const std::vector<double>& reference) {
  std::vector<double> r;
  for (std::size_t i = 0; i < std::min(candidate.size(), reference.size()); ++i) {
    if (reference[i] > 0) r.push_back(candidate[i] / reference[i]);
  }
  return r;
}

struct Comparison {
  Interval ratio;  // of candidate / reference times
  Verdict verdict = Verdict::kTooFewRepeats;
  double effect_pct = 0;  // (median ratio − 1) × 100: change in time, negative = candidate faster
  std::size_t pairs = 0;
};

// Compares two series of times (lower is better) repeat by repeat.
inline Comparison compare_paired(const std::vector<double>& candidate, const std::vector<double>& reference,
                                 double confidence = 0.95, int resamples = kBootstrapResamples,
                                 std::uint64_t seed = kBootstrapSeed) {
  Comparison c;
  const std::vector<double> ratios = paired_ratios(candidate, reference);
  c.pairs = ratios.size();
  c.ratio = bootstrap_median_ci(ratios, confidence, resamples, seed);
  c.effect_pct = (c.ratio.median - 1.0) * 100.0;
  if (c.pairs < kMinPairsForVerdict) {
    c.verdict = Verdict::kTooFewRepeats;
  } else if (c.ratio.high < 1.0) {
    c.verdict = Verdict::kAhead;
  } else if (c.ratio.low > 1.0) {
    c.verdict = Verdict::kBehind;
  } else {
    c.verdict = Verdict::kNoDifference;
  }
  return c;
}

}  // namespace frontsteal::stats
