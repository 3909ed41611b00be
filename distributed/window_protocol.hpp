// window_protocol.hpp — core/'s stealing protocol (stealing_protocol.hpp, try_lock.hpp, active_workers.hpp) as one
// rank runs it over the MPI-3 window, through rma_backend.hpp: the same source that Relacy, the execution-graph
// checker and the TSan stress tests run, instantiated with a backend whose words are window memory.
//
// ROLES: one WindowProtocol per rank. Its Owner claims from this rank's slot (local memory, no MPI call per claim);
// its Thief steals from another rank's slot through handles (one-sided operations); every rank's ActivitySlot is
// built around its home (core/state_home.hpp); the active count (I-T) lives in rank 0's part.
// The frame runner picks the instantiation at run time (F1's kind, a planted defect) and talks to it through
// this interface: one virtual call per claim (a few ns beside the claim's ~60 ns, measured in --calibrate).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "core/id_range.hpp"
#include "core/stealing_protocol.hpp"
#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

// Test hooks (never set in measured runs).
struct StealHooks {
  // After T1/T2 and before T3 (core's observer `planned`), wait (MPI_Get of the victim's Front, bounded by
  // overlap_timeout) until the victim has claimed an item of the planned share, so that the re-read (T4/T5)
  // has something to catch: the interleaving the skip-reread defect gets wrong, forced.
  bool force_overlap = false;
  std::chrono::milliseconds overlap_timeout{5000};
};

// Which core policy the run instantiates: Fenced, or a negative control of core/negative_controls.hpp.
enum class WindowPolicy : std::uint8_t { kFenced, kBrokenSkipsReread };

class WindowProtocol {
 public:
  virtual ~WindowProtocol() = default;

  // The owner (this rank's slot).
  virtual std::optional<ItemId> try_claim() = 0;
  // A batched claim: up to n ids of one list entry in one handshake (core's Owner::try_claim_up_to); and the
  // ids it would take if no thief intervened (Owner::unclaimed_run), to size a batch by cost.
  virtual std::optional<IdRange> try_claim_up_to(std::uint32_t n) = 0;
  virtual IdRange unclaimed_run() = 0;
  virtual void install(std::span<const IdRange> list) = 0;
  // Items of this rank's list not yet claimed by its owner and not taken by a thief (End read locally, as O2).
  virtual std::uint32_t unclaimed() = 0;
  // The thief: one attempt on `victim`'s slot; on kStolen, share() holds what to install.
  virtual StealOutcome try_steal(int victim, const StealHooks& hooks) = 0;
  virtual std::span<const IdRange> share() const = 0;
  // The active count in rank 0's part (A2, A1 on a thief's behalf, A3, E4).
  virtual void leave() = 0;
  virtual void join() = 0;
  virtual bool all_idle() = 0;
  virtual void rearm(std::uint32_t ranks) = 0;
  // Diagnostics: one-sided operations spent by steals that succeeded (rma_backend.hpp V1-V3: 7 without a wait at
  // T4), time spent waiting at T4, and polls there that found ListTransient raised.
  virtual std::uint64_t stolen_operations() const = 0;
  virtual double t4_wait_s() const = 0;
  virtual std::uint64_t t4_polls() const = 0;
  virtual std::string_view backend_name() const = 0;
  virtual std::string_view policy_name() const = 0;
};

// `win_sync_f1`: F1 is MPI_Win_sync as well as the CPU fence (rma_backend.hpp, G3).
std::unique_ptr<WindowProtocol> make_window_protocol(RmaWindow& win, int ranks, bool win_sync_f1, WindowPolicy policy);

// Whether thieves read a victim in one view (rma_backend.hpp V1; the default) or word by word (--thief-reads words,
// for comparison). Set before any steal.
void read_victims_in_views(bool on) noexcept;

// Negative control only (--plant-defect stale-view): the thief's view of a victim outlives its own stores and
// answers T5 (rma_backend.hpp, V1's control). Set before any steal.
void plant_stale_view(bool on) noexcept;

}  // namespace frontsteal::mpi
