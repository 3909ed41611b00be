// window_self_test.cpp — the start-up check of every one-sided operation's result (window_self_test.hpp).
#include "distributed/window_self_test.hpp"

#include <cstdint>
#include <cstdio>
#include <cstddef>
#include <cstring>
#include <thread>

#include "distributed/rank_watchdog.hpp"

namespace frontsteal::mpi {
namespace {

constexpr std::uint32_t kFrontMark = 0xF00D0000u;
constexpr std::uint32_t kLockMark = 0x10C00000u;
constexpr std::uint32_t kCountMark = 0xC0DE0000u;
constexpr std::uint32_t kPutMark = 0xABCD0000u;
constexpr std::uint32_t kActiveBase = 1000;
constexpr std::uint64_t kNextItemBase = 0x5EED00000000ull;  // beyond 32 bits: the 64-bit path is checked
constexpr std::uint32_t kEntryMark = 0xE0000000u;

// Records the first mismatch of this rank.
class Expect {
 public:
  explicit Expect(WindowSelfTest& r) : r_(r) {}
  template <class T>
  void equal(const char* what, int target, T got, T want) {
    if (got == want) return;
    if (r_.ok) {
      char text[200];
      std::snprintf(text, sizeof text, "%s on rank %d returned %lld, expected %lld", what, target,
                    static_cast<long long>(got), static_cast<long long>(want));
      r_.first_failure = text;
    }
    r_.ok = false;
  }

 private:
  WindowSelfTest& r_;
};

}  // namespace

WindowSelfTest run_window_self_test(RmaWindow& win, MPI_Comm comm) {
  int me = 0, ranks = 1;
  MPI_Comm_rank(comm, &me);
  MPI_Comm_size(comm, &ranks);
  const auto u = [](int r) { return static_cast<std::uint32_t>(r); };
  WindowSelfTest result;
  Expect expect(result);

  // Known values: local stores for the owner-written words, an accumulate for the accumulate-only lock word.
  win.local(kFront).store(kFrontMark + u(me), std::memory_order_relaxed);
  win.local(kEntryCount).store(kCountMark + u(me), std::memory_order_relaxed);
  win.local_entries()[0] = SegmentEntry{{kEntryMark + u(me), kEntryMark + u(me) + 7}, u(me)};
  win.accumulate_replace(me, kLock, kLockMark + u(me));
  if (me == 0) {
    win.accumulate_replace(0, kActive, kActiveBase);
    win.accumulate_replace(0, kNextItem, kNextItemBase);
  }
  win.sync();
  MPI_Barrier(comm);

  for (int t = 0; t < ranks; ++t) {
    const int q = (t + 1) % ranks;
    if (me == t) {
      expect.equal("MPI_Fetch_and_op(MPI_NO_OP) of LockList (L1)", q, win.atomic_read(q, kLock), kLockMark + u(q));
      expect.equal("MPI_Get of Front (T1)", q, win.get(q, kFront), kFrontMark + u(q));
      expect.equal("MPI_Get of the entry count", q, win.get(q, kEntryCount), kCountMark + u(q));
      expect.equal("MPI_Compare_and_swap of LockList (L2)", q,
                   win.compare_and_swap(q, kLock, kLockMark + u(q), kLockMark + u(q)), kLockMark + u(q));
      win.put(q, kEnd, kPutMark + u(t));
      SegmentEntry entry{};
      win.get_entries(q, 0, 1, &entry);
      expect.equal("MPI_Get of the list body (entry 0's begin)", q, entry.ids.begin, kEntryMark + u(q));
      expect.equal("MPI_Get of the list body (entry 0's flat_begin)", q, entry.flat_begin, u(q));
      std::byte header[kHeaderBytes];
      SegmentEntry viewed{};
      win.get_view(q, 1, header, &viewed);
      std::uint32_t front = 0, count = 0;
      std::memcpy(&front, header + kFront.disp, sizeof front);
      std::memcpy(&count, header + kEntryCount.disp, sizeof count);
      expect.equal("the thief's view, one MPI_Get (Front)", q, front, kFrontMark + u(q));
      expect.equal("the thief's view, one MPI_Get (the entry count)", q, count, kCountMark + u(q));
      expect.equal("the thief's view, one MPI_Get (entry 0's begin)", q, viewed.ids.begin, kEntryMark + u(q));
      const std::uint32_t before = win.fetch_and_op(0, kActive, std::uint32_t{1}, MPI_SUM);
      expect.equal("MPI_Fetch_and_op(MPI_SUM) of the active count (A1)", 0, before, kActiveBase + u(t));
      const std::uint64_t next = win.fetch_and_op(0, kNextItem, std::uint64_t{3}, MPI_SUM);
      expect.equal("MPI_Fetch_and_op(MPI_SUM) of the central counter (64-bit)", 0, next,
                   kNextItemBase + 3 * static_cast<std::uint64_t>(t));
    } else if (me == q) {
      std::this_thread::sleep_for(kTargetAsleep);  // no MPI call: a deferred operation cannot complete yet
    }
    MPI_Barrier(comm);
    note_progress();  // the watchdog (armed by the caller) names a turn whose operation never completes
    if (me == q) {
      win.sync();
      expect.equal("MPI_Put of End (T3), read by its target", t, win.local(kEnd).load(std::memory_order_acquire),
                   kPutMark + u(t));
    }
  }
  MPI_Barrier(comm);
  if (me == 0)
    expect.equal("the active count after every rank's MPI_SUM", 0, win.atomic_read(0, kActive), kActiveBase + u(ranks));

  // Everything back to zero, as the window was created.
  win.local(kFront).store(0u, std::memory_order_relaxed);
  win.local(kEnd).store(0u, std::memory_order_relaxed);
  win.local(kEntryCount).store(0u, std::memory_order_relaxed);
  win.local_entries()[0] = SegmentEntry{};
  win.accumulate_replace(me, kLock, 0u);
  if (me == 0) {
    win.accumulate_replace(0, kActive, std::uint32_t{0});
    win.accumulate_replace(0, kNextItem, std::uint64_t{0});
  }
  win.sync();
  int mine = result.ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, comm);
  result.ok = all == 1;
  MPI_Barrier(comm);
  return result;
}

}  // namespace frontsteal::mpi
