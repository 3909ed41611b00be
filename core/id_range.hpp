// id_range.hpp — contiguous ranges of item ids and the list algebra the protocol is specified with.
//
// Paper §4.2.2: "In practice, ActivityList is not implemented as a list of surface ids but as a list of id
// ranges." These are the pure, single-threaded operations on such lists: counting, splitting off the second
// half by item count across several ranges, appending with merging of adjacent ranges, normalising, and
// checking that a set of lists is a partition of [0, n). The concurrent protocol (stealing_protocol.hpp)
// implements the same split on shared state; tests/core/id_range_test.cpp pins the algebra down.
#pragma once

#include <algorithm>
#include <cstdint>
#include <ostream>
#include <span>
#include <vector>

namespace frontsteal {

using ItemId = std::uint32_t;
using WorkerId = std::uint32_t;

// Half-open range [begin, end) of item ids. Empty when begin == end.
struct IdRange {
  ItemId begin = 0;
  ItemId end = 0;

  constexpr std::uint32_t size() const noexcept { return end - begin; }
  constexpr bool empty() const noexcept { return begin == end; }
  friend constexpr bool operator==(const IdRange&, const IdRange&) = default;
};

inline std::ostream& operator<<(std::ostream& out, const IdRange& r) {
  return out << '[' << r.begin << ',' << r.end << ')';
}

using RangeList = std::vector<IdRange>;

inline std::uint64_t item_count(std::span<const IdRange> list) noexcept {
  std::uint64_t n = 0;
  for (const IdRange& r : list) n += r.size();
  return n;
}

// Appends r, extending the last range instead when r starts where it ends. Empty ranges are dropped, so a
// list built only with this function never holds one.
inline void append_merging(RangeList& list, IdRange r) {
  if (r.empty()) return;
  if (!list.empty() && list.back().end == r.begin) {
    list.back().end = r.end;
  } else {
    list.push_back(r);
  }
}

// Sorts by first id and merges ranges that touch. Overlapping ranges are merged too; callers that must not
// see overlap (a partition) check with is_partition() first.
inline RangeList normalized(RangeList list) {
  std::sort(list.begin(), list.end(), [](const IdRange& a, const IdRange& b) { return a.begin < b.begin; });
  RangeList out;
  out.reserve(list.size());
  for (const IdRange& r : list) {
    if (r.empty()) continue;
    if (!out.empty() && r.begin <= out.back().end) {
      out.back().end = std::max(out.back().end, r.end);
    } else {
      out.push_back(r);
    }
  }
  return out;
}

// The two parts of a list split at an item count: `kept` holds the first `keep` items, `taken` the rest,
// both in list order. A range straddling the split point is cut in two.
struct SplitLists {
  RangeList kept;
  RangeList taken;
};

inline SplitLists split_after(std::span<const IdRange> list, std::uint64_t keep) {
  SplitLists out;
  for (const IdRange& r : list) {
    if (keep >= r.size()) {
      append_merging(out.kept, r);
      keep -= r.size();
    } else if (keep > 0) {
      const auto cut = static_cast<ItemId>(r.begin + keep);
      append_merging(out.kept, {r.begin, cut});
      append_merging(out.taken, {cut, r.end});
      keep = 0;
    } else {
      append_merging(out.taken, r);
    }
  }
  return out;
}

// The number of items a thief leaves to the victim when `remaining` items are unprocessed: the thief takes
// the second half, rounded up, so a single remaining item can be stolen (the race the handshake resolves).
constexpr std::uint64_t items_left_to_victim(std::uint64_t remaining) noexcept { return remaining / 2; }

// Paper §4.2.2 line 651: "Delete the second half of unprocessed ActivityList[p_b]".
inline SplitLists split_second_half(std::span<const IdRange> list) {
  return split_after(list, items_left_to_victim(item_count(list)));
}

// True when the lists together cover every id of [0, n) exactly once.
inline bool is_partition(std::span<const RangeList> lists, ItemId n) {
  std::vector<IdRange> all;
  for (const RangeList& l : lists) all.insert(all.end(), l.begin(), l.end());
  std::erase_if(all, [](const IdRange& r) { return r.empty(); });
  std::sort(all.begin(), all.end(), [](const IdRange& a, const IdRange& b) { return a.begin < b.begin; });
  ItemId expected = 0;
  for (const IdRange& r : all) {
    if (r.begin != expected || r.end < r.begin) return false;
    expected = r.end;
  }
  return expected == n;
}

// Contiguous blocks, worker w gets [w*n/P, (w+1)*n/P): the default static allocation (§3's simplest).
inline std::vector<RangeList> block_allocation(ItemId n, WorkerId workers) {
  std::vector<RangeList> lists(workers);
  for (WorkerId w = 0; w < workers; ++w) {
    const auto b = static_cast<ItemId>(std::uint64_t{n} * w / workers);
    const auto e = static_cast<ItemId>(std::uint64_t{n} * (w + 1) / workers);
    append_merging(lists[w], {b, e});
  }
  return lists;
}

}  // namespace frontsteal
