// heap_offset.hpp — a block of random size held on the heap while an instance under measurement lives, so that
// what the instance allocates next lands at a random offset.
//
// Why: two instances of the same code can differ by a few per cent for as long as they live, because of where
// their memory landed (cache sets, pages, what shares a line with them: Mytkowicz, Diwan, Hauswirth & Sweeney,
// ASPLOS 2009; Curtsinger & Berger's STABILIZER, ASPLOS 2013). A measurement that builds fresh instances must
// also move them, or the allocator hands each new instance the memory the last one freed and the "fresh"
// instance sits exactly where the old one did. The block is 16 B to 96 KiB in 16-byte steps: below malloc's
// mmap threshold (128 KiB), so it comes from the same heap as the instance and shifts it.
//
// Use: construct the HeapOffset (or redraw() it), then the instance; destroy the instance, then the offset
// (hold both in one object, the offset declared first).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "measure/paired_comparison.hpp"

namespace frontsteal::measure {

class HeapOffset {
 public:
  HeapOffset() = default;
  // The size is drawn from (seed, draw): a run is reproducible, every instance of it at its own offset.
  HeapOffset(std::uint64_t seed, std::uint64_t draw) { redraw(seed, draw); }
  // A fresh offset: the old block is freed first, so the new one is drawn from the heap as it is now.
  void redraw(std::uint64_t seed, std::uint64_t draw) {
    block_.reset();
    stats::SplitMix64 rng(seed ^ (0x9e37'79b9'7f4a'7c15ull * (draw + 1)));
    bytes_ = 16 * (1 + rng.index(kMaxBytes / 16));
    block_ = std::make_unique<std::byte[]>(bytes_);
    block_[bytes_ - 1] = std::byte{1};  // touched, so the allocation is real
  }
  std::size_t bytes() const noexcept { return bytes_; }

  static constexpr std::size_t kMaxBytes = 96 * 1024;

 private:
  std::unique_ptr<std::byte[]> block_;
  std::size_t bytes_ = 0;
};

}  // namespace frontsteal::measure
