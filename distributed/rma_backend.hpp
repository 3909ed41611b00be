// rma_backend.hpp — an atomics backend of core/ whose words live in an MPI-3 window (rma_window.hpp): the
// stealing protocol of core/stealing_protocol.hpp runs across ranks unchanged, the same source the model
// checkers and the stress tests run.
//
// HOMES (core/state_home.hpp). RmaHome{window, rank} names rank `rank`'s part of the window. A rank builds one
// ActivitySlot per rank, each around its home: its own slot is local memory, every other slot is a set of
// handles (rank, displacement) that a thief reaches with one-sided operations. ActiveWorkers' count lives in
// rank 0's part (a memory word with a home, not a master: rank 0 runs no code for it).
//
// WHAT EACH ACCESS BECOMES (the word's kind decides; the site and its order come from the policy as everywhere)
//   Front, ListTransient, End, entry count, list body   on this rank's own part: std::atomic_ref (atomic words,
//       with the policy's order) or a plain copy (cells), no MPI call: the owner path O1..O4 stays wait-free
//       and MPI-free (G2). On another rank's part: MPI_Get / MPI_Put, each flushed (G1, G5).
//   LockList, the active count (accumulate-only words, G4): every access is an accumulate operation, even on
//       this rank's own part: load = MPI_Fetch_and_op(MPI_NO_OP), store = MPI_Accumulate(MPI_REPLACE),
//       exchange = MPI_Fetch_and_op(MPI_REPLACE), fetch_add/sub = MPI_Fetch_and_op(MPI_SUM), compare-exchange
//       = MPI_Compare_and_swap. A release store to an accumulate-only word of this rank's own part is preceded
//       by MPI_Win_sync (G3): it publishes what the owner wrote locally before it (install, then L3).
//   Fences: the CPU fence the policy names (as StdBackend); with OwnerFence::kWinSync the owner's F1 is also
//       MPI_Win_sync (G3, the standard's memory barrier). The thief's F2 needs no MPI call: T3's Put is flushed,
//       so it is complete at the target before T4's Get is issued (G5).
//   spin_pause (T4, an owner taking its own lock): yields the core after a burst, as StdBackend; with more
//       ranks than cores the rank waited for may be the one not running.
// A write to another rank's plain cell is a protocol error here (core writes list bodies only at install, into
// its own slot): the backend's invariant stops the run with the site's line.
//
// Backends are static: the fence's window (for MPI_Win_sync) is bound per process by an RmaFenceWindow scope.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/memory_order.hpp"
#include "core/site.hpp"
#include "core/source_location.hpp"
#include "core/state_home.hpp"
#include "core/std_backend.hpp"
#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

// Rank `rank`'s part of `window`.
struct RmaHome {
  RmaWindow* window = nullptr;
  int rank = 0;
};

// Where each word of core/state_home.hpp lies in a rank's part (rma_window.hpp's layout), and whether it is an
// accumulate-only word.
struct RmaPlace {
  MPI_Aint disp = 0;
  bool accumulate_only = false;
};
inline RmaPlace rma_place(StateWord word, std::uint32_t index = 0) noexcept {
  switch (word) {
    case StateWord::kFront: return {kFront.disp, false};
    case StateWord::kTransient: return {kTransient.disp, false};
    case StateWord::kEnd: return {kEnd.disp, false};
    case StateWord::kLock: return {kLock.disp, true};
    case StateWord::kEntryCount: return {kEntryCount.disp, false};
    case StateWord::kEntries: return {entry_disp(index), false};
    case StateWord::kActiveCount: return {kActive.disp, true};
  }
  return {};
}

// A handle to an atomic word (core's Backend::Atomic<T>).
template <class T>
class RmaAtomic {
 public:
  static_assert(std::is_same_v<T, std::uint32_t>, "the window's atomic words are u32");
  RmaAtomic(const RmaHome& home, StateWord word)
      : window_(home.window), rank_(home.rank), place_(rma_place(word)), local_(home.rank == home.window->rank()) {}

  RmaWindow& window() const noexcept { return *window_; }
  int rank() const noexcept { return rank_; }
  WinField<T> field() const noexcept { return {place_.disp}; }
  bool accumulate_only() const noexcept { return place_.accumulate_only; }
  bool local() const noexcept { return local_; }
  std::atomic_ref<T> ref() const noexcept { return window_->local(field()); }

 private:
  RmaWindow* window_;
  int rank_;
  RmaPlace place_;
  bool local_;
};

// A handle to a plain cell (core's Backend::Cell<T>): the entry count or one entry of the list body.
template <class T>
class RmaCell {
 public:
  static_assert(std::is_trivially_copyable_v<T>);
  RmaCell(const RmaHome& home, StateWord word, std::uint32_t index)
      : window_(home.window),
        rank_(home.rank),
        disp_(rma_place(word, index).disp),
        local_(home.rank == home.window->rank()) {}

  RmaWindow& window() const noexcept { return *window_; }
  int rank() const noexcept { return rank_; }
  MPI_Aint disp() const noexcept { return disp_; }
  bool local() const noexcept { return local_; }

 private:
  RmaWindow* window_;
  int rank_;
  MPI_Aint disp_;
  bool local_;
};

// F1 with OwnerFence::kWinSync is also MPI_Win_sync; kCpu keeps it a CPU fence (beyond the standard, G3).
enum class OwnerFence : std::uint8_t { kCpu, kWinSync };

template <OwnerFence F1 = OwnerFence::kCpu>
struct RmaBackend {
  static constexpr std::string_view kName = F1 == OwnerFence::kWinSync ? "mpi-rma (F1 = MPI_Win_sync)" : "mpi-rma";

  using Home = RmaHome;
  template <class T>
  using Atomic = RmaAtomic<T>;
  template <class T>
  using Cell = RmaCell<T>;
  using Where = SourceLocation;

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site, Where) {
    if (a.accumulate_only()) return a.window().atomic_read(a.rank(), a.field());
    if (a.local()) return a.ref().load(StdBackend::native(mo));
    return a.window().get(a.rank(), a.field());
  }
  template <class T>
  static void store(const Atomic<T>& a, T v, Mo mo, Site, Where) {
    if (a.accumulate_only()) {
      if (a.local() && releases(mo)) a.window().sync();  // G3: publish this rank's earlier local stores
      a.window().accumulate_replace(a.rank(), a.field(), v);
    } else if (a.local()) {
      a.ref().store(v, StdBackend::native(mo));
    } else {
      a.window().put(a.rank(), a.field(), v);
    }
  }
  template <class T>
  static T exchange(const Atomic<T>& a, T v, Mo, Site, Where w) {
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), v, MPI_REPLACE);
  }
  template <class T>
  static T fetch_add(const Atomic<T>& a, T v, Mo, Site, Where w) {
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), v, MPI_SUM);
  }
  template <class T>
  static T fetch_sub(const Atomic<T>& a, T v, Mo, Site, Where w) {
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), static_cast<T>(T{0} - v), MPI_SUM);  // unsigned wrap
  }
  template <class T>
  static bool compare_exchange(const Atomic<T>& a, T& expected, T desired, Mo, Mo, Site, Where w) {
    accumulate_word(a, w);
    const T found = a.window().compare_and_swap(a.rank(), a.field(), expected, desired);
    if (found == expected) return true;
    expected = found;
    return false;
  }

  static void fence(Fence f, Site site, Where where) {
    if (F1 == OwnerFence::kWinSync && site == Site::kOwnerStoreLoadFence && fence_window() != nullptr) {
      fence_window()->sync();  // G3
    }
    StdBackend::fence(f, site, where);
  }

  template <class T>
  static T read(const Cell<T>& c, Where) {
    T v;
    if (c.local()) {
      std::memcpy(&v, c.window().local_bytes(c.disp()), sizeof(T));
    } else {
      c.window().get_bytes(c.rank(), c.disp(), &v, sizeof(T));
    }
    return v;
  }
  template <class T>
  static void write(const Cell<T>& c, T v, Where w) {
    invariant(c.local(), "rma backend: a plain cell of another rank written (core writes only its own list)", w);
    std::memcpy(c.window().local_bytes(c.disp()), &v, sizeof(T));
  }

  static void invariant(bool holds, const char* what, Where where = Where::current()) noexcept {
    StdBackend::invariant(holds, what, where);
  }

  static void spin_pause(Site site, std::uint32_t spins) noexcept {
    if (site == Site::kThiefAwaitTransient) ++t4_polls();
    StdBackend::spin_pause(site, spins);
  }

  // Polls at T4 that found ListTransient raised, by this thread (a diagnostic for the run's report).
  static std::uint64_t& t4_polls() noexcept {
    thread_local std::uint64_t n = 0;
    return n;
  }

  // The window whose MPI_Win_sync is F1 (kWinSync); bound by RmaFenceWindow.
  static RmaWindow*& fence_window() noexcept {
    static RmaWindow* w = nullptr;
    return w;
  }

 private:
  static constexpr bool releases(Mo mo) noexcept {
    return mo == Mo::kRelease || mo == Mo::kAcqRel || mo == Mo::kSeqCst;
  }
  template <class T>
  static void accumulate_word(const Atomic<T>& a, Where w) {
    invariant(a.accumulate_only(), "rma backend: a read-modify-write on a word that is not accumulate-only (G4)", w);
  }
};

// Binds `window` as the window of F1's MPI_Win_sync for the scope's lifetime.
template <OwnerFence F1>
class RmaFenceWindow {
 public:
  explicit RmaFenceWindow(RmaWindow& window) { RmaBackend<F1>::fence_window() = &window; }
  ~RmaFenceWindow() { RmaBackend<F1>::fence_window() = nullptr; }
  RmaFenceWindow(const RmaFenceWindow&) = delete;
  RmaFenceWindow& operator=(const RmaFenceWindow&) = delete;
};

}  // namespace frontsteal::mpi
