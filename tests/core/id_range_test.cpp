// Range-list algebra (core/id_range.hpp): the single-threaded specification of "steal the second half".
#include "core/id_range.hpp"

#include <catch2/catch.hpp>

using frontsteal::IdRange;
using frontsteal::RangeList;

TEST_CASE("split_second_half takes the second half by item count across several ranges", "[core][range]") {
  const RangeList list{{0, 3}, {10, 12}, {20, 25}};  // 3 + 2 + 5 = 10 items
  const auto split = frontsteal::split_second_half(list);
  CHECK(split.kept == RangeList{{0, 3}, {10, 12}});
  CHECK(split.taken == RangeList{{20, 25}});

  const RangeList odd{{0, 2}, {5, 8}, {9, 11}};  // 7 items: victim keeps 3, thief takes 4
  const auto s2 = frontsteal::split_second_half(odd);
  CHECK(s2.kept == RangeList{{0, 2}, {5, 6}});
  CHECK(s2.taken == RangeList{{6, 8}, {9, 11}});
  CHECK(frontsteal::item_count(s2.kept) + frontsteal::item_count(s2.taken) == 7);
}

TEST_CASE("split_second_half of one item gives it to the thief, of nothing gives nothing", "[core][range]") {
  const auto one = frontsteal::split_second_half(RangeList{{7, 8}});
  CHECK(one.kept.empty());
  CHECK(one.taken == RangeList{{7, 8}});

  const auto none = frontsteal::split_second_half(RangeList{});
  CHECK(none.kept.empty());
  CHECK(none.taken.empty());
}

TEST_CASE("split_after cuts a range straddling the split point", "[core][range]") {
  const auto s = frontsteal::split_after(RangeList{{100, 110}}, 4);
  CHECK(s.kept == RangeList{{100, 104}});
  CHECK(s.taken == RangeList{{104, 110}});
}

TEST_CASE("append_merging merges adjacent ranges and drops empty ones", "[core][range]") {
  RangeList l;
  frontsteal::append_merging(l, {0, 4});
  frontsteal::append_merging(l, {4, 6});
  frontsteal::append_merging(l, {6, 6});
  frontsteal::append_merging(l, {8, 9});
  CHECK(l == RangeList{{0, 6}, {8, 9}});
}

TEST_CASE("normalized sorts and merges touching ranges", "[core][range]") {
  CHECK(frontsteal::normalized(RangeList{{8, 9}, {3, 5}, {0, 3}, {5, 5}, {9, 12}}) == RangeList{{0, 5}, {8, 12}});
  CHECK(frontsteal::normalized(RangeList{}).empty());
}

TEST_CASE("is_partition accepts exactly the partitions of 0 .. n-1", "[core][range]") {
  using Lists = std::vector<RangeList>;
  CHECK(frontsteal::is_partition(Lists{{{0, 3}}, {{3, 5}, {7, 9}}, {{5, 7}}}, 9));
  CHECK(frontsteal::is_partition(Lists{{}, {}}, 0));
  CHECK_FALSE(frontsteal::is_partition(Lists{{{0, 3}}, {{2, 5}}}, 5));  // 2 twice
  CHECK_FALSE(frontsteal::is_partition(Lists{{{0, 3}}, {{4, 5}}}, 5));  // 3 missing
  CHECK_FALSE(frontsteal::is_partition(Lists{{{0, 6}}}, 5));            // out of range
}

TEST_CASE("block_allocation partitions 0 .. n-1 for any worker count", "[core][range]") {
  for (frontsteal::ItemId n : {0u, 1u, 5u, 1000u}) {
    for (frontsteal::WorkerId p : {1u, 2u, 3u, 8u}) {
      INFO("n=" << n << " p=" << p);
      CHECK(frontsteal::is_partition(frontsteal::block_allocation(n, p), n));
    }
  }
}
