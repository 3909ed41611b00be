// execution_counter.hpp — the hook tests and stress drivers use to count how often each item ran.
//
// record() is called from the item function (any thread, relaxed atomic increment: the counts are read only
// after the frame, whose end orders every increment before the read). audit() reports lost items (ran 0
// times) and duplicated ones (ran 2+ times) and resets the counts for the next frame.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal {

struct ExecutionAudit {
  std::uint64_t items = 0;
  std::uint64_t lost = 0;                // items that never ran
  std::uint64_t duplicated = 0;          // items that ran more than once
  std::uint64_t extra_runs = 0;          // runs beyond the first, summed
  std::vector<ItemId> first_lost;        // up to 8 examples, for the failure message
  std::vector<ItemId> first_duplicated;  // up to 8 examples

  bool exactly_once() const noexcept { return lost == 0 && duplicated == 0; }
  bool at_least_once() const noexcept { return lost == 0; }

  // Item `item` ran `runs` times: counted as lost (0), duplicated (2 or more) or fine.
  void classify(ItemId item, std::uint32_t runs) {
    if (runs == 0) {
      ++lost;
      if (first_lost.size() < 8) first_lost.push_back(item);
    } else if (runs > 1) {
      ++duplicated;
      extra_runs += runs - 1;
      if (first_duplicated.size() < 8) first_duplicated.push_back(item);
    }
  }
};

inline std::ostream& operator<<(std::ostream& out, const ExecutionAudit& a) {
  out << "items=" << a.items << " lost=" << a.lost << " duplicated=" << a.duplicated << " extra_runs=" << a.extra_runs;
  if (!a.first_lost.empty()) {
    out << " lost_ids=";
    for (ItemId i : a.first_lost) out << i << ' ';
  }
  if (!a.first_duplicated.empty()) {
    out << " duplicated_ids=";
    for (ItemId i : a.first_duplicated) out << i << ' ';
  }
  return out;
}

class ExecutionCounter {
 public:
  explicit ExecutionCounter(ItemId items)
      : items_(items), runs_(std::make_unique<std::atomic<std::uint32_t>[]>(items)) {}

  void record(ItemId item) noexcept { runs_[item].fetch_add(1, std::memory_order::relaxed); }
  std::uint32_t runs(ItemId item) const noexcept { return runs_[item].load(std::memory_order::relaxed); }

  ExecutionAudit audit_and_reset() noexcept {
    ExecutionAudit a;
    a.items = items_;
    for (ItemId i = 0; i < items_; ++i) a.classify(i, runs_[i].exchange(0, std::memory_order::relaxed));
    return a;
  }

 private:
  ItemId items_;
  std::unique_ptr<std::atomic<std::uint32_t>[]> runs_;
};

}  // namespace frontsteal
