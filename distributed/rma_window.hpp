// rma_window.hpp — one MPI-3 window per run holding every rank's thief-visible stealing state, and the few
// one-sided operations the distributed protocols use (each completed with MPI_Win_flush, each counted in bytes).
// core/'s protocol reaches it through rma_backend.hpp, which maps each word of core/state_home.hpp to a field here.
//
// Layout of every rank's part of the window (byte displacements, disp_unit 1). It mirrors ActivitySlot
// (core/activity_list.hpp): Front, ListTransient and End share a line; LockList has its own; then the list body.
//   0    Front[p]            u32   owner writes locally (O3, I1); thieves MPI_Get (T1, T5)
//   4    ListTransient[p]    u32   owner writes locally (O1, O4); thieves MPI_Get (T4)
//   8    End[p]              u32   thieves MPI_Put (T3); owner reads locally (O2), writes at install (I2)
//   12   entry count         u32   owner writes locally at install, under its own LockList; thieves MPI_Get
//   64   LockList[p]         u32   accumulate operations only (MPI_Fetch_and_op MPI_REPLACE L2, MPI_Accumulate
//                                  MPI_REPLACE L3; no L1 probe, rma_backend.hpp V3), by thieves and by the owner
//                                  on itself: the standard makes only same-type accumulates atomic with each
//                                  other, so this word is never touched by a plain load, store, Get or Put
//   128  active              u32   rank 0's copy only: the termination count (A1-A3, E4), accumulates only
//   136  next item           u64   rank 0's copy only: the central-counter baseline, accumulates only
//   256  lifeline notice     u64   the frame is over (lifelines.hpp): other ranks MPI_Accumulate (REPLACE); the
//                                  rank reads it locally; reset by the rank (an accumulate on itself) between frames
//   264  lifeline invite     u64   a donor's invitation, same ownership as the notice
//   320  lifeline hungry[k]  u64   k < kMaxLifelines: rank (p - 2^k) mod P registered here, same ownership
//   512  entries[capacity]   SegmentEntry {begin, end, flat_begin} u32 x 3 each, same ownership as the entry count
// A thief's view of a victim (get_view): bytes [0, 16) and the first entries in ONE MPI_Get, through a derived
// datatype that skips the lock, the counters and the lifeline words (accumulate-only: no Get may touch them).
//
// MPI GUARANTEES RELIED ON (MPI 3.1 §11.4, §11.5, §11.7)
//   G1  Passive target: MPI_Win_lock_all once at start, MPI_Win_unlock_all at the end; every RMA operation is
//       completed at origin and target by MPI_Win_flush(target) before its result is used or the next protocol
//       step starts (§11.5.4). This is where the shared-memory protocol has its fences.
//   G2  The unified memory model (MPI_WIN_MODEL == MPI_WIN_UNIFIED, checked at start, the run refuses
//       otherwise): public and private copies are one memory, so the owner may read and write its own part of
//       the window with plain (here: std::atomic_ref) loads and stores, with no MPI call, and a completed
//       Put is visible to the owner's loads, a local store to later Gets (§11.4, "eventually").
//   G3  MPI_Win_sync on the owner orders its local stores and loads with respect to the public copy (§11.7;
//       the unified-model example 11.21 uses it as the memory barrier): the publication of an installed list
//       always, and the owner's F1 (between O1 and O2) with --owner-fence win-sync. By DEFAULT F1 is a seq_cst
//       CPU fence only (--owner-fence cpu), which is beyond the standard: Open MPI's osc/sm MPI_Win_sync is that
//       same barrier plus a call into the progress engine, and with mpi_yield_when_idle (needed with more
//       ranks than cores) that call yields the core on every claim — measured at milliseconds per claim
//       beside two busy loops, against ~60 ns without them.
//   G4  Accumulate operations (MPI_Compare_and_swap, MPI_Fetch_and_op, MPI_Accumulate) on the same location
//       with the same basic datatype are atomic with respect to each other (§11.7.1): the lock, the
//       termination count and the central counter rely on it.
//   G5  MPI_Win_flush completes an operation AT THE TARGET (§11.5.4): after T3's Put and its flush, the new
//       End is in the victim's memory before the thief issues T4's Get. With G3 on the owner this is the
//       store-buffering (Dekker) handshake of stealing_protocol.hpp with F1 = MPI_Win_sync, F2 = the flush.
// ONE ACCESSOR PER OPERATION. Each field is a WinField<T> (its type and byte displacement); every one-sided
// operation is one template over the field (get, put, compare_and_swap, fetch_and_op, accumulate_replace),
// so the datatype, the flush and the byte count are written once, not once per field and type.
// BEYOND THE STANDARD (stated, not hidden): MPI 3.1 calls a Get or Put concurrent with a local store to the
// same bytes "conflicting" and leaves the outcome undefined; we rely on an aligned 4-byte word being read and
// written whole (true of Open MPI's osc/sm and osc/rdma over shared memory, where a Get is a copy from mapped
// memory, and of RDMA NICs for aligned words), and on G3/G5 giving a total order to the handshake (osc/sm:
// both are full memory barriers). That is the price of the wait-free owner path: the alternative, the owner
// updating its own words with MPI_Accumulate on itself, puts MPI calls on every claim.
#pragma once

#include <mpi.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/activity_list.hpp"
#include "core/id_range.hpp"

namespace frontsteal::mpi {

// A word of a rank's part of the window: its C++ type and byte displacement. The type picks the MPI datatype.
template <class T>
struct WinField {
  using Value = T;
  MPI_Aint disp;
};

template <class T>
MPI_Datatype mpi_datatype() noexcept;
template <>
inline MPI_Datatype mpi_datatype<std::uint32_t>() noexcept {
  return MPI_UINT32_T;
}
template <>
inline MPI_Datatype mpi_datatype<std::int32_t>() noexcept {
  return MPI_INT32_T;
}
template <>
inline MPI_Datatype mpi_datatype<std::uint64_t>() noexcept {
  return MPI_UINT64_T;
}

inline constexpr WinField<std::uint32_t> kFront{0};
inline constexpr WinField<std::uint32_t> kTransient{4};
inline constexpr WinField<std::uint32_t> kEnd{8};
inline constexpr WinField<std::uint32_t> kLock{64};
inline constexpr WinField<std::uint32_t> kActive{128};
inline constexpr WinField<std::uint64_t> kNextItem{136};
inline constexpr WinField<std::uint32_t> kEntryCount{12};
inline constexpr WinField<std::uint64_t> kLifelineNotice{256};
inline constexpr WinField<std::uint64_t> kLifelineInvite{264};
inline constexpr std::uint32_t kMaxLifelines = 24;  // ranks up to 2^24
inline constexpr WinField<std::uint64_t> lifeline_hungry(std::uint32_t k) noexcept {
  return {320 + 8 * static_cast<MPI_Aint>(k)};
}
inline constexpr MPI_Aint kEntries = 512;
// The thief-visible header that a view reads whole: Front, ListTransient, End and the entry count.
inline constexpr MPI_Aint kHeaderBytes = 16;

// A list entry lies in the window as core's SegmentEntry (activity_list.hpp): three u32, no padding.
static_assert(sizeof(SegmentEntry) == 12 && std::is_trivially_copyable_v<SegmentEntry>);
inline constexpr MPI_Aint entry_disp(std::uint32_t index) noexcept {
  return kEntries + static_cast<MPI_Aint>(index) * static_cast<MPI_Aint>(sizeof(SegmentEntry));
}

// Throws with the MPI error string: the window is created with MPI_ERRORS_RETURN so a dead peer becomes an
// error we can report (and exit non-zero on) instead of an abort with no context.
inline void check_mpi(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw std::runtime_error(std::string(what) + ": " + std::string(text, static_cast<std::size_t>(len)));
}

// The window, its base pointer (this rank's part) and the one-sided operations, each flushed (G1).
class RmaWindow {
 public:
  RmaWindow(MPI_Comm comm, std::uint32_t capacity) : capacity_(capacity) {
    const MPI_Aint bytes = kEntries + static_cast<MPI_Aint>(capacity) * static_cast<MPI_Aint>(sizeof(SegmentEntry));
    MPI_Info info;
    MPI_Info_create(&info);
    // Every accumulate on a location uses one datatype and op family: let the implementation use hardware
    // (or shared-memory) atomics for them.
    MPI_Info_set(info, "accumulate_ordering", "none");
    MPI_Comm_rank(comm, &rank_);
    check_mpi(MPI_Win_allocate(bytes, 1, info, comm, &base_, &win_), "MPI_Win_allocate");
    MPI_Info_free(&info);
    MPI_Win_set_errhandler(win_, MPI_ERRORS_RETURN);
    int* model = nullptr;
    int flag = 0;
    MPI_Win_get_attr(win_, MPI_WIN_MODEL, &model, &flag);
    unified_ = flag != 0 && *model == MPI_WIN_UNIFIED;
    std::memset(base_, 0, static_cast<std::size_t>(bytes));
    MPI_Barrier(comm);  // every rank's zeroed memory exists before anyone's first access
    check_mpi(MPI_Win_lock_all(MPI_MODE_NOCHECK, win_), "MPI_Win_lock_all");
  }
  RmaWindow(const RmaWindow&) = delete;
  RmaWindow& operator=(const RmaWindow&) = delete;
  ~RmaWindow() {
    for (auto& [entries, t] : view_types_)
      if (t != MPI_DATATYPE_NULL) MPI_Type_free(&t);
    // MPI_Win_free is collective. While an exception unwinds this rank, the others are elsewhere (in a
    // barrier, in the next frame): the free would wait for them until the watchdog ended the job, and the
    // exception's message would never be printed. The handler that caught it ends the job with MPI_Abort.
    if (std::uncaught_exceptions() > 0) return;
    MPI_Win_unlock_all(win_);
    MPI_Win_free(&win_);
  }

  bool unified() const noexcept { return unified_; }
  int rank() const noexcept { return rank_; }  // this process's rank in the window's communicator
  MPI_Win handle() const noexcept { return win_; }
  std::uint32_t capacity() const noexcept { return capacity_; }
  std::uint64_t bytes_moved() const noexcept { return bytes_; }
  // One-sided operations this rank issued (each Get, Put, accumulate and view is one, whatever its size).
  std::uint64_t operations() const noexcept { return operations_; }

  // ---- this rank's own part: local memory (G2) ----
  template <class T>
  std::atomic_ref<T> local(WinField<T> f) noexcept {
    return std::atomic_ref<T>(*reinterpret_cast<T*>(static_cast<char*>(base_) + f.disp));
  }
  SegmentEntry* local_entries() noexcept {
    return reinterpret_cast<SegmentEntry*>(static_cast<char*>(base_) + kEntries);
  }
  void* local_bytes(MPI_Aint disp) noexcept { return static_cast<char*>(base_) + disp; }
  void sync() { check_mpi(MPI_Win_sync(win_), "MPI_Win_sync"); }  // G3

  // ---- one-sided operations on any rank's part (G1: each is flushed before it returns) ----
  template <class T>
  T get(int rank, WinField<T> f) {
    T v{};
    check_mpi(MPI_Get(&v, 1, mpi_datatype<T>(), rank, f.disp, 1, mpi_datatype<T>(), win_), "MPI_Get");
    return completed(rank, sizeof(T), v);
  }
  template <class T>
  void put(int rank, WinField<T> f, T v) {
    check_mpi(MPI_Put(&v, 1, mpi_datatype<T>(), rank, f.disp, 1, mpi_datatype<T>(), win_), "MPI_Put");
    completed(rank, sizeof(T), 0);
  }
  // Compare-and-swap (G4): returns the value found.
  template <class T>
  T compare_and_swap(int rank, WinField<T> f, T expected, T desired) {
    T found{};
    check_mpi(MPI_Compare_and_swap(&desired, &expected, &found, mpi_datatype<T>(), rank, f.disp, win_),
              "MPI_Compare_and_swap");
    return completed(rank, 2 * sizeof(T), found);
  }
  // Fetch-and-op (G4): MPI_SUM adds `operand` and returns the old value; MPI_NO_OP is an atomic read.
  template <class T>
  T fetch_and_op(int rank, WinField<T> f, T operand, MPI_Op op) {
    T found{};
    check_mpi(MPI_Fetch_and_op(&operand, &found, mpi_datatype<T>(), rank, f.disp, op, win_), "MPI_Fetch_and_op");
    return completed(rank, op == MPI_NO_OP ? sizeof(T) : 2 * sizeof(T), found);
  }
  // `count` fetch-and-ops on one word issued back to back and completed by one flush; returns the last old
  // value. Counted as `count` operations (--calibrate's pipelined row).
  template <class T>
  T fetch_and_op_burst(int rank, WinField<T> f, T operand, MPI_Op op, std::size_t count) {
    burst_results_.resize(count * sizeof(T));
    T* found = reinterpret_cast<T*>(burst_results_.data());
    for (std::size_t k = 0; k < count; ++k)
      check_mpi(MPI_Fetch_and_op(&operand, &found[k], mpi_datatype<T>(), rank, f.disp, op, win_), "MPI_Fetch_and_op");
    const T last = completed(rank, count * 2 * sizeof(T), found[count - 1]);
    operations_ += count - 1;
    return last;
  }
  template <class T>
  T atomic_read(int rank, WinField<T> f) {
    return fetch_and_op(rank, f, T{}, MPI_NO_OP);
  }
  // An atomic write (G4: the word is only ever touched by accumulate operations).
  template <class T>
  void accumulate_replace(int rank, WinField<T> f, T v) {
    check_mpi(MPI_Accumulate(&v, 1, mpi_datatype<T>(), rank, f.disp, 1, mpi_datatype<T>(), MPI_REPLACE, win_),
              "MPI_Accumulate");
    completed(rank, sizeof(T), 0);
  }
  void get_entries(int rank, std::uint32_t first, std::uint32_t count, SegmentEntry* out) {
    if (count == 0) return;
    const int ints = static_cast<int>(count * 3);
    check_mpi(MPI_Get(out, ints, MPI_UINT32_T, rank, entry_disp(first), ints, MPI_UINT32_T, win_), "MPI_Get entries");
    completed(rank, count * sizeof(SegmentEntry), 0);
  }
  // A thief's view of `rank`'s part in one operation: the header (kHeaderBytes: Front, ListTransient, End, the entry
  // count) into `header`, and entries [0, entries) into `out`. One MPI_Get whose target datatype is two blocks,
  // so the accumulate-only words between them are not read (G4).
  void get_view(int rank, std::uint32_t entries, std::byte* header, SegmentEntry* out) {
    MPI_Datatype& target = view_type(entries);
    std::byte* buffer = view_buffer(entries);
    const int bytes = static_cast<int>(kHeaderBytes + entries * sizeof(SegmentEntry));
    check_mpi(MPI_Get(buffer, bytes, MPI_BYTE, rank, 0, 1, target, win_), "MPI_Get view");
    completed(rank, static_cast<std::size_t>(bytes), 0);
    std::memcpy(header, buffer, kHeaderBytes);
    if (entries > 0) std::memcpy(out, buffer + kHeaderBytes, entries * sizeof(SegmentEntry));
  }
  // `bytes` bytes at `disp` of `rank`'s part, as they lie (a list entry: core's SegmentEntry).
  void get_bytes(int rank, MPI_Aint disp, void* out, std::size_t bytes) {
    const int n = static_cast<int>(bytes);
    check_mpi(MPI_Get(out, n, MPI_BYTE, rank, disp, n, MPI_BYTE, win_), "MPI_Get");
    completed(rank, bytes, 0);
  }
  void flush(int rank) { check_mpi(MPI_Win_flush(rank, win_), "MPI_Win_flush"); }

  // Test hook (--plant-defect read-before-flush; never in measured runs): results are read before MPI_Win_flush,
  // as the old code did. Invisible where MPI_Get copies at once (osc/sm); caught by the self-test elsewhere.
  void plant_read_before_flush(bool on) noexcept { read_before_flush_ = on; }

 private:
  // G1: the operation is complete at origin and target before its value is used; counts its payload bytes.
  // `result` is the operation's result buffer, taken by reference and read only AFTER the flush: until then
  // MPI may not have written it. (Taking it by value would read it before the flush: on osc/sm, which
  // copies inside MPI_Get, nothing shows; over osc/pt2pt (TCP), where data arrives at the flush, every Get,
  // fetch-and-op and CAS returns 0, so thieves see empty lists and never steal, the lock CAS always
  // "succeeds", and the central counter hands out item 0 forever. window_self_test.hpp checks every
  // operation's result at start; plant_read_before_flush() is that bug, for its negative control.)
  template <class T>
  T completed(int rank, std::size_t bytes, const T& result) {
    T before_flush{};
    if (read_before_flush_) before_flush = result;  // only the planted defect touches it before the flush
    flush(rank);
    bytes_ += bytes;
    operations_ += 1;
    return read_before_flush_ ? before_flush : result;
  }

  // The view's target datatype for `entries` entries (built once per size, freed with the window) and its buffer.
  MPI_Datatype& view_type(std::uint32_t entries) {
    MPI_Datatype& t = view_types_.try_emplace(entries, MPI_DATATYPE_NULL).first->second;
    if (t == MPI_DATATYPE_NULL) {
      const int lengths[2] = {static_cast<int>(kHeaderBytes), static_cast<int>(entries * sizeof(SegmentEntry))};
      const MPI_Aint displacements[2] = {0, kEntries};
      check_mpi(MPI_Type_create_hindexed(entries > 0 ? 2 : 1, lengths, displacements, MPI_BYTE, &t),
                "MPI_Type_create_hindexed");
      check_mpi(MPI_Type_commit(&t), "MPI_Type_commit");
    }
    return t;
  }
  std::byte* view_buffer(std::uint32_t entries) {
    const std::size_t bytes = kHeaderBytes + entries * sizeof(SegmentEntry);
    if (view_buffer_.size() < bytes) view_buffer_.resize(bytes);
    return view_buffer_.data();
  }

  void* base_ = nullptr;
  MPI_Win win_ = MPI_WIN_NULL;
  std::map<std::uint32_t, MPI_Datatype> view_types_;  // by entry count: a few sizes in a run
  std::vector<std::byte> view_buffer_;
  std::vector<std::byte> burst_results_;  // fetch_and_op_burst's results, written by MPI until the flush
  std::uint64_t operations_ = 0;
  std::uint32_t capacity_;
  int rank_ = 0;
  bool unified_ = false;
  bool read_before_flush_ = false;
  std::uint64_t bytes_ = 0;
};

}  // namespace frontsteal::mpi
