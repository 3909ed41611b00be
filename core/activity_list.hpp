// activity_list.hpp — the thief-visible state of one worker: ActivityList[p], Front[p], ListTransient[p],
// LockList[p] (paper §4.2).
//
// The list body is a segment: an array of id ranges laid end to end in "flat" positions 0, 1, 2, ...
// Front and End are flat positions. The owner claims positions from Front upwards; thieves take the tail by
// lowering End. Flat positions let a thief split "by item count across ranges" with one binary search, and
// let the owner walk its list with an O(1) cursor.
//
// Ownership (who writes / who reads, with which site labels; the orders come from the policy):
//   front        owner writes (O3 per claim, I1 at install)  | thieves read under lock (T1, T5)
//   transient    owner writes (O1, O4)                        | thieves read under lock (T4)
//   end          thieves write under lock (T3); owner writes under its own lock (I2)
//                                                             | owner reads (O2) without lock; thieves (T2)
//   lock         thieves (L1-L3), owner only when idle        |
//   entries,     owner writes, only under its own lock and only at install
//   entry_count                                               | owner reads; thieves read under lock
// front, transient and end share a cache line: the owner writes the first two and reads the third on every
// claim, and thieves touch the line only while stealing. The lock has its own line so that thieves
// contending for it do not steal the owner's line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <ostream>

#include "core/id_range.hpp"
#include "core/labelled_access.hpp"
#include "core/state_home.hpp"
#include "core/try_lock.hpp"

namespace frontsteal {

inline constexpr std::size_t kCacheLine = 64;

// One range of the segment and the flat position of its first id.
struct SegmentEntry {
  IdRange ids;
  std::uint32_t flat_begin = 0;
  constexpr std::uint32_t flat_end() const noexcept { return flat_begin + ids.size(); }
};

inline std::ostream& operator<<(std::ostream& out, const SegmentEntry& e) {
  return out << e.ids << '@' << e.flat_begin;
}

template <class Backend, class Policy>
struct ActivitySlot {
  template <class T>
  using Atomic = typename Backend::template Atomic<T>;
  template <class T>
  using Cell = typename Backend::template Cell<T>;
  using Home = HomeOf<Backend>;

  // `home`: where the words live (state_home.hpp); the default builds them in place.
  explicit ActivitySlot(std::uint32_t max_entries, const Home& home = {})
      : front(atomic_word<Backend>(home, StateWord::kFront, 0u)),
        transient(atomic_word<Backend>(home, StateWord::kTransient, 0u)),
        end(atomic_word<Backend>(home, StateWord::kEnd, 0u)),
        lock(home),
        entries(home, StateWord::kEntries, max_entries),
        entry_count(cell_word<Backend, std::uint32_t>(home, StateWord::kEntryCount)),
        capacity(max_entries) {}
  ActivitySlot(const ActivitySlot&) = delete;
  ActivitySlot& operator=(const ActivitySlot&) = delete;

  alignas(kCacheLine) Atomic<std::uint32_t> front;  // Front[p]: flat positions below it are claimed
  Atomic<std::uint32_t> transient;                  // ListTransient[p]: 1 while a claim is in flight
  Atomic<std::uint32_t> end;                        // End of ActivityList[p] (flat position)

  alignas(kCacheLine) TryLock<Backend, Policy> lock;  // LockList[p]

  alignas(kCacheLine) CellArray<Backend, SegmentEntry> entries;  // the list body
  Cell<std::uint32_t> entry_count;
  const std::uint32_t capacity;  // immutable: every list of a run fits (one range holds at least one item)
};

}  // namespace frontsteal
