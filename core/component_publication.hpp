// component_publication.hpp — greedy rendering's triangle publication (paper §5.2) and the reclamation the
// paper leaves out: tessellators publish a connected component's triangles all at once, a pusher that never
// waits draws whatever is published, and a buffer is rewritten only after the pusher can no longer be reading it.
//
// Roles (each a type-free role of this one class; a thread may play several):
//   pusher       one thread. Per update u = 1, 2, …: begin_update() (P1), read(c) once per component (P2), draws
//                the slot it got, end_update() (P3). Never waits: wait-free, a bounded number of steps per update.
//   tessellator  any worker of the frame. Writes one surface's triangles into back_slot(c), then
//                finish_surface(c) (W1); the one whose surface completes c publishes it (W2) and stamps the slot
//                it retired (W3). Wait-free.
//   driver       one thread, between frames (tessellators quiescent). prepare_frame() picks each component's
//                back slot among the free ones (D1); it is the only role that can wait, and only on the pusher.
// Ownership: every component has `slots` buffers (≥ 2; 3 lets tessellation run a frame ahead of a slow pusher
//   without waiting). At any time a slot is exactly one of: published (the pusher may read it), retired
//   (stamped; the pusher may still be reading it), free (no one reads it), back (this frame's tessellators write
//   it). The data of a slot (triangles) lives outside this class, indexed by (component, slot).
// Invariants:
//   I1 a component's published slot holds the triangles of exactly one frame, for every one of its surfaces
//      (no torn component: the pusher never mixes old and new triangles inside a component);
//   I2 a slot is written only while no pusher update can be reading it (no use after reuse);
//   I3 the published frame of a component never goes back.
// Linearization points: W2 publishes component c for the pusher; P2 is the pusher's read of c for update u.
// Reclamation (quiescent-state based, one reader): the tessellator that retires slot r by W2 then reads
//   Started (W3) into stamp(r). Only pusher updates numbered ≤ stamp(r) can hold r: an update u > stamp(r)
//   announced itself (P1) after W3 read Started in the total order S of seq_cst operations, so its P2 comes
//   after W2 in S and reads the new slot or a later one. The driver treats r as free once Completed ≥ stamp(r)
//   (D1 reads Completed, P3 wrote it after the pusher's last read of r).
// Labelled orders and their pairings (PublicationOrders in publication_policies.hpp gives the sound ones):
//   P1 Started := u           store  seq_cst  } store→load on each side (the Dekker pattern again, as with
//   P2 read Published[c]      load   seq_cst  }  ListTransient): P1→P2 on the pusher, W2→W3 on the
//   W2 Published[c] := back   rmw    seq_cst  }  tessellator; weakening any one to acquire/release lets a
//   W3 read Started           load   seq_cst  }  slot be reused under the pusher (the checker shows it).
//   W1 Done[c] += 1           rmw    acq_rel  — release: this surface's triangles; acquire (last one): all of c's.
//   P3 Completed := u         store  release  — pairs with D1 acquire: reads of retired slots before their reuse.
//   P2 also acquires what W2 released: the component's triangles.
// Progress: pusher and tessellators are wait-free. The driver waits only when every non-published slot of a
//   component is still held by an unfinished pusher update, i.e. for at most one pusher update (with 3 slots it
//   waits only if the pusher has not finished one update during a whole tessellation frame); a preempted or
//   stopped pusher stalls tessellation there, never the other way round.
// Cracks: components are swapped independently, so a crack can open between two components while the view
//   moves, as the paper accepts (§5.2); within a component, I1 holds.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/labelled_access.hpp"
#include "core/policies.hpp"
#include "core/site.hpp"

namespace frontsteal {

using ComponentId = std::uint32_t;
using SlotIndex = std::uint32_t;

template <class Backend, class Policy>
class ComponentPublication {
  using A = Access<Backend, Policy>;
  template <class T>
  using Atomic = typename Backend::template Atomic<T>;
  template <class T>
  using Cell = typename Backend::template Cell<T>;

 public:
  static constexpr SlotIndex kNothing = 0xffff'ffffu;  // Published[c] before c's first publication

  // surfaces_per_component[c] = how many surfaces component c has (each ≥ 1).
  ComponentPublication(const std::vector<std::uint32_t>& surfaces_per_component, SlotIndex slots)
      : components_(static_cast<ComponentId>(surfaces_per_component.size())),
        slots_(slots),
        per_component_(std::make_unique<PerComponent[]>(components_)),
        stamps_(std::make_unique<Cell<std::uint64_t>[]>(static_cast<std::size_t>(components_) * slots)) {
    Backend::invariant(slots >= 2, "a component needs at least two slots (one published, one written)");
    for (ComponentId c = 0; c < components_; ++c) {
      Backend::invariant(surfaces_per_component[c] >= 1, "a component without surfaces");
      PerComponent& pc = per_component_[c];
      A::write(pc.surfaces, std::uint64_t{surfaces_per_component[c]});
      A::write(pc.back, kNothing);
      A::write(pc.front, kNothing);
      A::write(pc.done_target, std::uint64_t{0});
    }
    for (std::size_t k = 0; k < static_cast<std::size_t>(components_) * slots; ++k)
      A::write(stamps_[k], std::uint64_t{0});
  }

  ComponentId components() const noexcept { return components_; }
  SlotIndex slots() const noexcept { return slots_; }

  // ---- driver ---------------------------------------------------------------------------------------------
  // Before each frame, with no tessellator running: gives every component a back slot that no pusher update
  // can be reading. Returns for how many components it had to wait for the pusher (0 in the common case).
  std::uint64_t prepare_frame() {
    std::uint64_t waits = 0;
    for (ComponentId c = 0; c < components_; ++c) {
      PerComponent& pc = per_component_[c];
      // Last frame's back slot was published by the end of that frame (every surface finished).
      const SlotIndex front = A::read(pc.back) == kNothing ? A::read(pc.front) : A::read(pc.back);
      A::write(pc.front, front);
      SlotIndex chosen = kNothing;
      for (std::uint32_t spins = 0;; ++spins) {
        const std::uint64_t completed = A::template load<Site::kDriverReadCompleted>(completed_);  // D1
        for (SlotIndex s = 0; s < slots_ && chosen == kNothing; ++s) {
          if (s == front) continue;
          const bool grace_passed = A::read(stamp(c, s)) <= completed;
          if (grace_passed || has(Policy::defects(), Defect::kReuseWithoutGrace)) chosen = s;
        }
        if (chosen != kNothing) break;
        waits += spins == 0;  // one wait per component that had to wait, however long
        Backend::spin_pause(Site::kDriverReadCompleted, spins);
      }
      A::write(pc.back, chosen);
      A::write(pc.done_target, A::read(pc.done_target) + A::read(pc.surfaces));
    }
    return waits;
  }

  // ---- tessellator ----------------------------------------------------------------------------------------
  // Where this frame's triangles of component c go. Constant during a frame.
  SlotIndex back_slot(ComponentId c) const noexcept { return A::read(per_component_[c].back); }

  // After one surface of c has been written into back_slot(c). Returns true if this call published c.
  bool finish_surface(ComponentId c) {
    PerComponent& pc = per_component_[c];
    const std::uint64_t before = A::template fetch_add<Site::kWriterCountDown>(pc.done, std::uint64_t{1});  // W1
    const bool last = before + 1 == A::read(pc.done_target);
    if (!last && !has(Policy::defects(), Defect::kPublishEachSurface)) return false;
    const SlotIndex back = A::read(pc.back);
    const SlotIndex retired = A::template exchange<Site::kWriterPublish>(pc.published, back);  // W2
    if (retired != back && retired != kNothing) {
      A::write(stamp(c, retired), A::template load<Site::kWriterReadStarted>(started_));  // W3
    }
    return true;
  }

  // ---- pusher ---------------------------------------------------------------------------------------------
  // Returns the update's number (1, 2, …).
  std::uint64_t begin_update() {
    ++update_;
    A::template store<Site::kPusherAnnounce>(started_, update_);  // P1
    return update_;
  }
  // The slot to draw for component c in this update (kNothing: not yet published). Read it once per update.
  SlotIndex read(ComponentId c) const {
    return A::template load<Site::kPusherReadPublished>(per_component_[c].published);  // P2
  }
  void end_update() { A::template store<Site::kPusherComplete>(completed_, update_); }  // P3

 private:
  struct PerComponent {
    alignas(64) Atomic<SlotIndex> published{kNothing};  // Published[c]: written by W2, read by P2
    Atomic<std::uint64_t> done{0};                      // Done[c]: surfaces of c finished, over all frames
    Cell<std::uint64_t> surfaces;                       // constant
    Cell<SlotIndex> back;                               // driver writes between frames; tessellators read
    Cell<SlotIndex> front;                              // driver only: the slot published by the last completed frame
    Cell<std::uint64_t> done_target;  // driver writes between frames: Done[c] after this frame's last surface
  };

  Cell<std::uint64_t>& stamp(ComponentId c, SlotIndex s) { return stamps_[static_cast<std::size_t>(c) * slots_ + s]; }

  const ComponentId components_;
  const SlotIndex slots_;
  std::unique_ptr<PerComponent[]> per_component_;
  std::unique_ptr<Cell<std::uint64_t>[]> stamps_;   // stamp(c, s): W3 writes, driver reads between frames
  alignas(64) Atomic<std::uint64_t> started_{0};    // Started: P1 writes, W3 reads
  alignas(64) Atomic<std::uint64_t> completed_{0};  // Completed: P3 writes, D1 reads
  std::uint64_t update_ = 0;                        // pusher only
};

}  // namespace frontsteal
