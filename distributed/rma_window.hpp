// rma_window.hpp — one MPI-3 window per run holding every rank's thief-visible stealing state, and the few
// one-sided operations the distributed protocols use (each completed with MPI_Win_flush, each counted in bytes).
//
// Layout of every rank's part of the window (byte displacements, disp_unit 1). It mirrors ActivitySlot
// (core/activity_list.hpp): Front, ListTransient and End share a line; LockList has its own; then the list body.
//   0    Front[p]            u32   owner writes locally (O3, I1); thieves MPI_Get (T1, T5)
//   4    ListTransient[p]    u32   owner writes locally (O1, O4); thieves MPI_Get (T4)
//   8    End[p]              u32   thieves MPI_Put (T3); owner reads locally (O2), writes at install (I2)
//   64   LockList[p]         u32   accumulate operations only (MPI_Compare_and_swap L2, MPI_Fetch_and_op
//                                  MPI_NO_OP L1, MPI_Accumulate MPI_REPLACE L3), by thieves and by the owner
//                                  on itself: the standard makes only same-type accumulates atomic with each
//                                  other, so this word is never touched by a plain load, store, Get or Put
//   128  active              i32   rank 0's copy only: the termination count (A1-A3, E4), accumulates only
//   136  next item           u64   rank 0's copy only: the central-counter baseline, accumulates only
//   192  entry count         u32   owner writes locally at install, under its own LockList; thieves MPI_Get
//   256  entries[capacity]   {begin, end, flat_begin} u32 x 3 each, same ownership as the entry count
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
#include <stdexcept>
#include <string>

#include "core/id_range.hpp"

namespace frontsteal::mpi {

inline constexpr MPI_Aint kFront = 0;
inline constexpr MPI_Aint kTransient = 4;
inline constexpr MPI_Aint kEnd = 8;
inline constexpr MPI_Aint kLock = 64;
inline constexpr MPI_Aint kActive = 128;
inline constexpr MPI_Aint kNextItem = 136;
inline constexpr MPI_Aint kEntryCount = 192;
inline constexpr MPI_Aint kEntries = 256;

// One list entry as it lies in the window: a range of ids and the flat position of its first id.
struct WinEntry {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
  std::uint32_t flat_begin = 0;
  std::uint32_t flat_end() const noexcept { return flat_begin + (end - begin); }
};
static_assert(sizeof(WinEntry) == 12);

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
    const MPI_Aint bytes = kEntries + static_cast<MPI_Aint>(capacity) * static_cast<MPI_Aint>(sizeof(WinEntry));
    MPI_Info info;
    MPI_Info_create(&info);
    // Every accumulate on a location uses one datatype and op family: let the implementation use hardware
    // (or shared-memory) atomics for them.
    MPI_Info_set(info, "accumulate_ordering", "none");
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
    MPI_Win_unlock_all(win_);
    MPI_Win_free(&win_);
  }

  bool unified() const noexcept { return unified_; }
  MPI_Win handle() const noexcept { return win_; }
  std::uint32_t capacity() const noexcept { return capacity_; }
  std::uint64_t bytes_moved() const noexcept { return bytes_; }

  // ---- this rank's own part: local memory (G2) ----
  std::atomic_ref<std::uint32_t> local_u32(MPI_Aint disp) noexcept {
    return std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(static_cast<char*>(base_) + disp));
  }
  WinEntry* local_entries() noexcept { return reinterpret_cast<WinEntry*>(static_cast<char*>(base_) + kEntries); }
  void sync() { check_mpi(MPI_Win_sync(win_), "MPI_Win_sync"); }  // G3

  // ---- one-sided operations on any rank's part (G1: each is flushed before it returns) ----
  std::uint32_t get_u32(int rank, MPI_Aint disp) {
    std::uint32_t v = 0;
    check_mpi(MPI_Get(&v, 1, MPI_UINT32_T, rank, disp, 1, MPI_UINT32_T, win_), "MPI_Get");
    flush(rank);
    bytes_ += 4;
    return v;
  }
  void put_u32(int rank, MPI_Aint disp, std::uint32_t v) {
    check_mpi(MPI_Put(&v, 1, MPI_UINT32_T, rank, disp, 1, MPI_UINT32_T, win_), "MPI_Put");
    flush(rank);
    bytes_ += 4;
  }
  void get_entries(int rank, std::uint32_t first, std::uint32_t count, WinEntry* out) {
    if (count == 0) return;
    const int ints = static_cast<int>(count * 3);
    check_mpi(MPI_Get(out, ints, MPI_UINT32_T, rank, kEntries + static_cast<MPI_Aint>(first) * 12, ints,
                      MPI_UINT32_T, win_), "MPI_Get entries");
    flush(rank);
    bytes_ += count * 12ull;
  }
  // Compare-and-swap (G4): returns the value found.
  std::uint32_t cas_u32(int rank, MPI_Aint disp, std::uint32_t expected, std::uint32_t desired) {
    std::uint32_t found = 0;
    check_mpi(MPI_Compare_and_swap(&desired, &expected, &found, MPI_UINT32_T, rank, disp, win_),
              "MPI_Compare_and_swap");
    flush(rank);
    bytes_ += 8;
    return found;
  }
  std::uint32_t atomic_read_u32(int rank, MPI_Aint disp) {
    std::uint32_t found = 0;
    std::uint32_t dummy = 0;
    check_mpi(MPI_Fetch_and_op(&dummy, &found, MPI_UINT32_T, rank, disp, MPI_NO_OP, win_), "MPI_Fetch_and_op");
    flush(rank);
    bytes_ += 4;
    return found;
  }
  void atomic_write_u32(int rank, MPI_Aint disp, std::uint32_t v) {
    check_mpi(MPI_Accumulate(&v, 1, MPI_UINT32_T, rank, disp, 1, MPI_UINT32_T, MPI_REPLACE, win_),
              "MPI_Accumulate");
    flush(rank);
    bytes_ += 4;
  }
  std::int32_t fetch_add_i32(int rank, MPI_Aint disp, std::int32_t delta) {
    std::int32_t found = 0;
    check_mpi(MPI_Fetch_and_op(&delta, &found, MPI_INT32_T, rank, disp, MPI_SUM, win_), "MPI_Fetch_and_op");
    flush(rank);
    bytes_ += 8;
    return found;
  }
  std::int32_t atomic_read_i32(int rank, MPI_Aint disp) {
    std::int32_t found = 0;
    std::int32_t dummy = 0;
    check_mpi(MPI_Fetch_and_op(&dummy, &found, MPI_INT32_T, rank, disp, MPI_NO_OP, win_), "MPI_Fetch_and_op");
    flush(rank);
    bytes_ += 4;
    return found;
  }
  void atomic_write_i32(int rank, MPI_Aint disp, std::int32_t v) {
    check_mpi(MPI_Accumulate(&v, 1, MPI_INT32_T, rank, disp, 1, MPI_INT32_T, MPI_REPLACE, win_), "MPI_Accumulate");
    flush(rank);
    bytes_ += 4;
  }
  std::uint64_t fetch_add_u64(int rank, MPI_Aint disp, std::uint64_t delta) {
    std::uint64_t found = 0;
    check_mpi(MPI_Fetch_and_op(&delta, &found, MPI_UINT64_T, rank, disp, MPI_SUM, win_), "MPI_Fetch_and_op");
    flush(rank);
    bytes_ += 16;
    return found;
  }
  void atomic_write_u64(int rank, MPI_Aint disp, std::uint64_t v) {
    check_mpi(MPI_Accumulate(&v, 1, MPI_UINT64_T, rank, disp, 1, MPI_UINT64_T, MPI_REPLACE, win_),
              "MPI_Accumulate");
    flush(rank);
    bytes_ += 8;
  }
  void flush(int rank) { check_mpi(MPI_Win_flush(rank, win_), "MPI_Win_flush"); }

 private:
  void* base_ = nullptr;
  MPI_Win win_ = MPI_WIN_NULL;
  std::uint32_t capacity_;
  bool unified_ = false;
  std::uint64_t bytes_ = 0;
};

}  // namespace frontsteal::mpi
