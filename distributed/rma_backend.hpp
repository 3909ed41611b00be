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
// ONE VIEW PER STEAL (V1-V3). A thief's reads under the victim's LockList, T1, T2, the entry count and the list
// body, are one MPI_Get (RmaWindow::get_view: the header and the first entries), not one round trip each:
//   V1  The load at T1 (Site::kThiefReadFront) of another rank's Front takes the view and answers from it; the
//       load at T2 and reads of that rank's entry count and entries answer from the view (an entry beyond it is
//       an MPI_Get of its own, the view kept). Every other access by this thread to another rank's part, every
//       accumulate and every fence ends the view: T3's Put, A1, F2, T4, T5, L3; so T4 and T5 are always fresh
//       operations, after T3's flush (G5). The owner path's plain words (this rank's own part) leave it alone:
//       they are not the victim's, and O1-O4 stay the plain loads and stores they were.
//   V2  Why it is the sequential code: core's thief reads these words after L2, holding the victim's LockList.
//       While it holds it, End, the entry count and the body are written by no one (stealing_protocol.hpp I1,
//       I2: thieves and installs write them only under that lock), so one Get returns what T2 and the body
//       reads would return at any moment of the lock; Front may move (O3) during the Get, and T1 reads it at
//       some moment after L2, the race the protocol already allows (T1 sizes the share, T5 corrects it).
//   V3  The lock probe is skipped (kSkipLockProbe, try_lock.hpp): over one-sided operations it is a round trip
//       that saves nothing; L2's exchange answers the same question.
// A successful steal is then L2, the view, A1, T3, T4 (once per poll), T5, L3: 7 one-sided operations, where the
// word-by-word reads took 5 + log2(entries) + the entries copied. Its negative control (plant_stale_view: the
// view outlives the thief's stores and answers T5, a T5 that reads Front as it was at T1) duplicates items the
// victim claims during the steal; the forced-overlap audit catches it (tests/CMakeLists.txt).
//
// A write to another rank's plain cell is a protocol error here (core writes list bodies only at install, into
// its own slot): the backend's invariant stops the run with the site's line.
//
// Backends are static: the fence's window (for MPI_Win_sync) is bound per process by an RmaFenceWindow scope.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

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

  // V3: L1 would be a round trip of its own (try_lock.hpp).
  static constexpr bool kSkipLockProbe = true;

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site site, Where) {
    if (a.local() && !a.accumulate_only()) return a.ref().load(StdBackend::native(mo));  // the owner path: no view
    if (!a.accumulate_only()) {
      if (site == Site::kThiefReadFront && read_views())
        return view().take(a.window(), a.rank()).word(a.field().disp);  // V1: T1
      if (view_covers(a.window(), a.rank()) && (site == Site::kThiefReadEnd || stale_view_answers(site)))
        return view().word(a.field().disp);  // V1: T2 (and T5 under the planted defect only)
    }
    end_view();
    if (a.accumulate_only()) return a.window().atomic_read(a.rank(), a.field());
    return a.window().get(a.rank(), a.field());
  }
  template <class T>
  static void store(const Atomic<T>& a, T v, Mo mo, Site, Where) {
    if (!a.local() || a.accumulate_only()) end_view();  // the owner path's own words leave the view alone
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
    end_view();
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), v, MPI_REPLACE);
  }
  template <class T>
  static T fetch_add(const Atomic<T>& a, T v, Mo, Site, Where w) {
    end_view();
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), v, MPI_SUM);
  }
  template <class T>
  static T fetch_sub(const Atomic<T>& a, T v, Mo, Site, Where w) {
    end_view();
    accumulate_word(a, w);
    return a.window().fetch_and_op(a.rank(), a.field(), static_cast<T>(T{0} - v), MPI_SUM);  // unsigned wrap
  }
  template <class T>
  static bool compare_exchange(const Atomic<T>& a, T& expected, T desired, Mo, Mo, Site, Where w) {
    end_view();
    accumulate_word(a, w);
    const T found = a.window().compare_and_swap(a.rank(), a.field(), expected, desired);
    if (found == expected) return true;
    expected = found;
    return false;
  }

  static void fence(Fence f, Site site, Where where) {
    end_view();
    if (F1 == OwnerFence::kWinSync && site == Site::kOwnerStoreLoadFence && fence_window() != nullptr) {
      fence_window()->sync();  // G3
    }
    StdBackend::fence(f, site, where);
  }

  template <class T>
  static T read(const Cell<T>& c, Where) {
    T v;
    if (!c.local() && view_covers(c.window(), c.rank()) && view().answer(c.disp(), &v, sizeof(T))) return v;  // V1
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

  // Whether T1 takes a view (V1; the default). Off: word-by-word reads, one operation each, for comparison.
  static bool& read_views() noexcept {
    static bool on = true;
    return on;
  }
  // Negative control only (never in measured runs): the view survives the thief's own stores and answers T5.
  static bool& plant_stale_view() noexcept {
    static bool planted = false;
    return planted;
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
  // This thread's view of one victim's part (V1): its header words and its first entries, as one Get read them.
  class ThiefView {
   public:
    // Reads `rank`'s part of `window` (one operation) and makes it the view.
    ThiefView& take(RmaWindow& window, int rank) {
      entries_.resize(std::min(window.capacity(), std::max(kFirstEntries, widest_)));
      window.get_view(rank, static_cast<std::uint32_t>(entries_.size()), header_, entries_.data());
      widest_ = std::max(widest_, std::min(window.capacity(), word(kEntryCount.disp)));
      viewed() = {&window, rank};
      return *this;
    }
    std::uint32_t word(MPI_Aint disp) const noexcept {
      std::uint32_t w = 0;
      std::memcpy(&w, header_ + disp, sizeof w);
      return w;
    }
    // Copies the cell at `disp` from the view; false when the view does not hold it.
    bool answer(MPI_Aint disp, void* out, std::size_t bytes) const noexcept {
      if (disp + static_cast<MPI_Aint>(bytes) <= kHeaderBytes) {
        std::memcpy(out, header_ + disp, bytes);
        return true;
      }
      const MPI_Aint body = static_cast<MPI_Aint>(entries_.size() * sizeof(SegmentEntry));
      if (disp < kEntries || disp + static_cast<MPI_Aint>(bytes) > kEntries + body) return false;
      std::memcpy(out, reinterpret_cast<const std::byte*>(entries_.data()) + (disp - kEntries), bytes);
      return true;
    }

   private:
    // Entries a view reads at least (768 bytes); more once a victim's list was seen longer.
    static constexpr std::uint32_t kFirstEntries = 64;
    std::byte header_[kHeaderBytes]{};
    std::vector<SegmentEntry> entries_;
    std::uint32_t widest_ = 0;
  };
  static ThiefView& view() noexcept {
    thread_local ThiefView v;
    return v;
  }
  // Which part this thread's view holds (window null: none). Trivially initialised, so checking and ending it
  // costs a thread-local load or store, not the guarded initialisation of the view's buffers.
  struct Viewed {
    const RmaWindow* window = nullptr;
    int rank = -1;
  };
  static Viewed& viewed() noexcept {
    thread_local constinit Viewed v{};
    return v;
  }
  static bool view_covers(const RmaWindow& window, int rank) noexcept {
    return viewed().window == &window && viewed().rank == rank;
  }
  static void end_view() noexcept {
    if (!plant_stale_view()) viewed().window = nullptr;
  }
  static bool stale_view_answers(Site site) noexcept { return plant_stale_view() && site == Site::kThiefRereadFront; }

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
