// publication_policies.hpp — memory-order policies of greedy rendering's triangle publication
// (component_publication.hpp): the sound one, and planted-defect negative controls.
//
// The publication protocol has its own sites (P*, W*, D* in site.hpp); these policies give orders to those
// sites only. Like the stealing policies, they are read by Access<Backend, Policy> and by the model checker's
// run-time table (models_check/table_policy.hpp), which weakens one site at a time to show each order is needed.
#pragma once

#include <string_view>

#include "core/memory_order.hpp"
#include "core/policies.hpp"
#include "core/site.hpp"

namespace frontsteal {

// The sound orders. Two reasons for each (site labels as in component_publication.hpp):
//   P1 seq_cst, P2 seq_cst, W2 seq_cst, W3 seq_cst   the reclamation handshake is a store→load pattern on each
//       side (pusher: P1 then P2; last tessellator: W2 then W3). Only if both pairs are in the single total
//       order S does a pusher update that the tessellator did not see in W3 see the new slot in P2.
//   P2 (acquire part), W2 (release part)   the pusher sees every triangle of the slot it reads.
//   W1 acq_rel   the last tessellator of a component acquires every other tessellator's triangles (release
//       sequence on Done[c]) before it publishes them.
//   P3 release, D1 acquire   the pusher's reads of a retired slot happen before the frame that rewrites it.
struct PublicationOrders {
  static constexpr std::string_view kName = "Publication";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site s) noexcept {
    switch (s) {
      case Site::kPusherAnnounce:
      case Site::kPusherReadPublished:
      case Site::kWriterPublish:
      case Site::kWriterReadStarted: return Mo::kSeqCst;
      case Site::kPusherComplete: return Mo::kRelease;
      case Site::kWriterCountDown: return Mo::kAcqRel;
      case Site::kDriverReadCompleted: return Mo::kAcquire;
      default: return acquire_release_order(s);
    }
  }
  static constexpr Fence fence(Site) noexcept { return Fence::kNone; }
};

// The frame driver hands a retired slot back to the tessellators as soon as it is no longer published, without
// waiting for the pusher to pass a later update: the pusher may still be drawing it (use after reuse).
struct BrokenReuseWithoutGrace : PublicationOrders {
  static constexpr std::string_view kName = "Broken:ReuseWithoutGrace";
  static constexpr Defect defects() noexcept { return Defect::kReuseWithoutGrace; }
};

// Every tessellator swaps its component in when its own surface is written, not the last one: the pusher can
// draw a component whose surfaces come from different frames (a torn component).
struct BrokenPublishEachSurface : PublicationOrders {
  static constexpr std::string_view kName = "Broken:PublishEachSurface";
  static constexpr Defect defects() noexcept { return Defect::kPublishEachSurface; }
};

}  // namespace frontsteal
