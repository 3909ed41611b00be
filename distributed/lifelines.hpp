// lifelines.hpp — how hier's dry ranks find work and learn that a frame is over without polling every rank: a
// low-degree lifeline graph (Saraswat, Kambadur, Kodali, Grove & Krishnamoorthy, "Lifeline-based global load
// balancing", PPoPP 2011), with invitations instead of pushed work, so that every item still moves through core's
// protocol (the steal) and nothing else.
//
// ROLES (one Lifelines per rank, used only by the rank's main thread: MPI_THREAD_FUNNELED)
//   hungry rank  its rank list and workers dry, one round of random victims failed. It registers at each of its
//                lifelines, the ranks (r + 2^k) mod P for 2^k < P (an accumulate of its registration number into
//                the buddy's hungry[k]), reads the global count (A3), and then waits on its own window words: no
//                remote operation while it waits.
//   donor        between items its main thread compares its hungry[k] words with the registrations it has
//                served; for a new one, with at least 2 unclaimed items in its rank list, it invites rank
//                (d - 2^k) mod P (an accumulate of (d + 1) << 32 | registration into that rank's invite word).
//   invited      a waiting rank that reads a new invitation makes one steal attempt on the donor (core's Thief);
//                if it gets nothing it registers again (a new number) and reads the count again.
//   the notice   a rank that learns the frame is over (its own A3 reads 0, or its notice word is set) tells its
//                children in the binomial tree rooted at rank 0 (rank i's children: i + 2^j for every 2^j > i);
//                a rank that learned it from the count also tells rank 0.
//
// INVARIANTS
//   L1  Every A2 of a rank is followed by an A3 of that rank before the rank waits (register, then read the
//       count, then wait): the rank whose A2 takes the count to 0 reads the 0. A count of 0 stays 0 (A1 needs a
//       victim holding work), so the frame's end is found.
//   L2  Whoever learns the frame is over forwards the notice (L2's tree), and rank 0 always learns (from the
//       rank that read the count, or by reading it): by induction over the tree every rank learns, in at most
//       ceil(log2 P) + 1 hops.
//   L3  Registrations and invitations are numbered and never cleared within a frame: a word is written only by
//       accumulates (rma_window.hpp, G4) and compared with the last value its reader saw, so no write is lost
//       to a reset. A rank resets its own words (accumulates on itself) between frames, when no other rank
//       writes them: every rank is then between the frame-done and the next frame-start barrier, and every
//       write of the frame was flushed (completed at its target) before its writer reached the done barrier.
//   Exactly once is core's: lifelines only decide who steals from whom, and when.
// BEYOND THE STANDARD (as End, rma_window.hpp): a rank reads its own lifeline words with plain atomic loads
// while other ranks accumulate into them (an aligned 8-byte word read and written whole: osc/sm, RDMA NICs).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "distributed/rma_window.hpp"

namespace frontsteal::mpi {

class Lifelines {
 public:
  // `drops_notice`: the negative control (--plant-defect lifeline-drops-notice): tell_frame_over tells nobody.
  Lifelines(RmaWindow& win, int rank, int ranks, bool drops_notice = false);

  // Between frames, before the frame-start barrier: this rank's words back to 0 (L3), its own state reset.
  void reset_for_next_frame();

  // ---- the hungry rank ----
  void register_hungry();               // a new registration at every lifeline
  std::optional<int> new_invitation();  // the donor of an invitation not seen before
  bool notice_seen();                   // another rank said the frame is over
  // The frame is over (learned from the count when `from_count`): tell the tree (L2); once per frame.
  void tell_frame_over(bool from_count);

  // ---- the donor (between items) ----
  // Invites every rank registered here since it was last served, while `has_spare()` (at least 2 unclaimed
  // items in the rank list). Cheap when nobody is registered: a few local loads.
  void invite_hungry(const std::function<bool()>& has_spare);

 private:
  RmaWindow& win_;
  int rank_, ranks_;
  std::vector<int> lifelines_;         // (rank + 2^k) mod P
  std::vector<std::uint64_t> served_;  // the last registration invited, per hungry[k]
  std::uint64_t registration_ = 0, last_invitation_ = 0;
  bool told_ = false;
  bool drops_notice_;
};

}  // namespace frontsteal::mpi
