// item_sampler.hpp — the harness's timing of a sample of single items, for the loss account: what an item's
// work costs, what the harness's own per-item checks cost, and what a scheduler spends between two items of
// one worker (its claim), without a clock read on every item.
//
// A fixed set of items is sampled: one in kStride, chosen by a seeded hash of the id, the same set in every arm
// of a run (the serial loop, the limit's copies, every scheduler), so a frame's sampled work in two arms is the
// same surfaces' work and their ratio is the work's inflation from one arm to the other (Olivier et al., SC'12:
// work time inflation). On a sampled item the arm's item function reads the clock three times: on entry, after
// the harness's checks, after the work; the entry read of the NEXT item the same worker runs closes a gap (the
// scheduler's claim and the call between them). Every interval holds one clock read's own cost, which is
// measured once (clock_cost_ns) and taken out.
//
// A worker's Lane is written by that worker only during a frame and read by the harness between frames (the
// scheduler's end of frame orders the writes before the read).
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace frontsteal::measure {

// What a set of frames' samples add up to: the sampled items' work and checks, their count, and the gaps.
struct ItemSamples {
  double work_ns = 0;    // Σ over sampled items of the work (clock cost taken out)
  double checks_ns = 0;  // Σ over sampled items of the harness's checks before the work
  std::uint64_t items = 0;
  std::vector<float> gaps_ns;  // one per closed gap: from a sampled item's end to its worker's next item's start

  ItemSamples& operator+=(const ItemSamples& o) {
    work_ns += o.work_ns;
    checks_ns += o.checks_ns;
    items += o.items;
    gaps_ns.insert(gaps_ns.end(), o.gaps_ns.begin(), o.gaps_ns.end());
    return *this;
  }
  // The harness's checks per item (mean over the samples; 0 without samples).
  double checks_per_item_ns() const { return items ? checks_ns / static_cast<double>(items) : 0.0; }
  // A scheduler's time between two items of one worker within one of its claims (a drain of the stealing
  // owner's list, a chunk): the mean of the gaps without their largest 2 %. A gap that spans the end of a claim
  // (the next chunk's claim, a search for work, a steal) is not the per-item claim, and is timed by those terms.
  double gap_per_item_ns() const {
    if (gaps_ns.empty()) return 0;
    std::vector<float> g = gaps_ns;
    const std::size_t keep = g.size() - g.size() / 50;
    std::nth_element(g.begin(), g.begin() + static_cast<std::ptrdiff_t>(keep - 1), g.end());
    double sum = 0;
    for (std::size_t i = 0; i < keep; ++i) sum += std::max(0.0f, g[i]);
    return sum / static_cast<double>(keep);
  }
};

class ItemSampler {
 public:
  static constexpr std::uint32_t kStride = 64;

  // Per worker: the open gap and this frame's sums.
  struct alignas(64) Lane {
    std::int64_t open_since = 0;  // the end of this worker's last sampled item, while its next item is awaited
    ItemSamples frame;
  };

  ItemSampler(std::uint32_t items, std::uint32_t workers, std::uint64_t seed)
      : sampled_(items, 0), lanes_(std::max<std::uint32_t>(workers, 1)) {
    for (std::uint32_t id = 0; id < items; ++id) {
      sampled_[id] = mix(seed ^ (std::uint64_t{id} * 0x9E3779B97F4A7C15ull)) % kStride == 0;
    }
    for (Lane& l : lanes_) l.frame.gaps_ns.reserve(items / kStride + 64);
    clock_cost_ns_ = measure_clock_cost();
  }

  static std::int64_t now() noexcept {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }

  bool sampled(std::uint32_t id) const noexcept { return sampled_[id] != 0; }
  std::uint32_t sampled_count() const noexcept {
    return static_cast<std::uint32_t>(std::count(sampled_.begin(), sampled_.end(), std::uint8_t{1}));
  }
  Lane& lane(std::uint32_t w) noexcept { return lanes_[w]; }
  std::uint32_t lanes() const noexcept { return static_cast<std::uint32_t>(lanes_.size()); }
  // What one clock read adds to an interval measured with two of them (median of back-to-back pairs).
  double clock_cost_ns() const noexcept { return clock_cost_ns_; }

  // Runs one item on worker w: checks() then work(), both timed when the item is sampled; closes w's open gap.
  template <class Checks, class Work>
  void run(std::uint32_t id, std::uint32_t w, Checks&& checks, Work&& work) {
    Lane& l = lanes_[w];
    if (!sampled_[id]) [[likely]] {
      if (l.open_since != 0) [[unlikely]]
        close_gap(l, now());
      checks();
      work();
      return;
    }
    const std::int64_t entry = now();
    if (l.open_since != 0) close_gap(l, entry);
    checks();
    const std::int64_t checked = now();
    work();
    const std::int64_t done = now();
    l.frame.checks_ns += std::max(0.0, static_cast<double>(checked - entry) - clock_cost_ns_);
    l.frame.work_ns += std::max(0.0, static_cast<double>(done - checked) - clock_cost_ns_);
    ++l.frame.items;
    l.open_since = done;
  }

  // Every lane's samples since the last call, summed; the lanes start afresh (no gap stays open across frames).
  ItemSamples take_frame() {
    ItemSamples out;
    for (Lane& l : lanes_) {
      out += l.frame;
      l.frame.work_ns = l.frame.checks_ns = 0;
      l.frame.items = 0;
      l.frame.gaps_ns.clear();
      l.open_since = 0;
    }
    return out;
  }

 private:
  void close_gap(Lane& l, std::int64_t t) {
    l.frame.gaps_ns.push_back(static_cast<float>(static_cast<double>(t - l.open_since) - clock_cost_ns_));
    l.open_since = 0;
  }
  static std::uint64_t mix(std::uint64_t x) {  // splitmix64's finalizer
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }
  static double measure_clock_cost() {
    std::vector<std::int64_t> d(2001);
    for (auto& v : d) {
      const std::int64_t a = now();
      v = now() - a;
    }
    std::nth_element(d.begin(), d.begin() + 1000, d.end());
    return static_cast<double>(d[1000]);
  }

  std::vector<std::uint8_t> sampled_;
  std::vector<Lane> lanes_;
  double clock_cost_ns_ = 0;
};

}  // namespace frontsteal::measure
