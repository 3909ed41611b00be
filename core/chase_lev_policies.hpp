// chase_lev_policies.hpp — memory-order policies of the Chase–Lev deque (chase_lev_deque.hpp): the sound one,
// from Lê, Pop, Cohen & Zappa Nardelli (PPoPP'13, Fig. 1), and planted-defect negative controls.
//
// The deque has its own sites (B*, K*, S*, H* in site.hpp, Protocol::kChaseLev); these policies give orders to
// those sites only (any other site gets plain acquire/release, and never meets the deque). Like the other
// policies, they are read by Access<Backend, Policy> and by the model checker's run-time table
// (models_check/table_policy.hpp), which weakens one site at a time.
#pragma once

#include <string_view>

#include "core/memory_order.hpp"
#include "core/policies.hpp"
#include "core/site.hpp"

namespace frontsteal {

// Lê et al.'s orders (their label in parentheses). Why each is there:
//   B2 (P1) read top: acquire   pairs with the release part of a thief's S5 (seq_cst CAS): a thief's S4 read of
//       buffer[t] happens before the owner overwrites that slot after wrapping around. Without it the thief
//       could read the new element (a load-buffering outcome of the C++ model).
//   B4 (P3) release fence       with S3 acquire: a thief that sees the new bottom sees the element (and what the
//       owner wrote before pushing it: the payload).
//   K3 (T3) seq_cst fence, S2 seq_cst fence   the store→load handshake: the owner's K2 (bottom := b - 1) then
//       K4 (read top) against a thief's S1 (read top) then S3 (read bottom). Without a fence on both sides the
//       owner can miss a steal that advanced top while the thief misses the reservation: both take the same
//       element (the second-to-last one, see chase_lev_deque.hpp).
//   K6 (T5), S5 CAS seq_cst     one winner for one element (any order gives that); seq_cst as in the paper, which
//       proves the orders correct as a set, not each one necessary (the kill matrix says which the checker can
//       show).
//   S1 read top: acquire        as in the paper.
//   S3 read bottom: acquire     pairs with B4 (above).
//   Everything else relaxed: the owner's reads of its own bottom (B1, K1), the slot accesses (B3, K5, S4: the
//       element is published by B4/S3, the slot is atomic only because a losing thief may read it while the
//       owner rewrites it), the restores of bottom (K7, K8: the owner's own variable; a thief that reads the old
//       value finds top > bottom or loses its CAS) and size_hint (H1, H2: a racy statistic).
//   CAS failure orders are relaxed (labelled_access.hpp).
struct ChaseLevOrders {
  static constexpr std::string_view kName = "ChaseLev";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site s) noexcept {
    switch (s) {
      case Site::kPushReadBottom:
      case Site::kPushWriteSlot:
      case Site::kPushPublishBottom:
      case Site::kTakeReadBottom:
      case Site::kTakeReserveBottom:
      case Site::kTakeReadTop:
      case Site::kTakeReadSlot:
      case Site::kTakeRestoreEmpty:
      case Site::kTakeRestoreLast:
      case Site::kStealReadSlot:
      case Site::kHintReadBottom:
      case Site::kHintReadTop: return Mo::kRelaxed;
      case Site::kPushReadTop:
      case Site::kStealReadTop:
      case Site::kStealReadBottom: return Mo::kAcquire;
      case Site::kTakeClaimLast:
      case Site::kStealClaim: return Mo::kSeqCst;
      default: return acquire_release_order(s);
    }
  }
  static constexpr Fence fence(Site s) noexcept {
    switch (s) {
      case Site::kPushReleaseFence: return Fence::kRelease;
      case Site::kTakeFence:
      case Site::kStealFence: return Fence::kSeqCst;
      default: return Fence::kNone;
    }
  }
};

// Negative controls: each must fail the model checker (models_check/chaselev_main.cpp).

// The owner's StoreLoad fence is gone (K3 none): the owner can miss a steal while the thief misses the owner's
// reservation, and both take the same element.
struct BrokenTakeWithoutFence : ChaseLevOrders {
  static constexpr std::string_view kName = "Broken:TakeWithoutFence";
  static constexpr Fence fence(Site s) noexcept {
    return s == Site::kTakeFence ? Fence::kNone : ChaseLevOrders::fence(s);
  }
};

// The owner keeps the last element without the CAS on top (K6 skipped): a thief that read the old bottom steals
// it too.
struct BrokenTakeLastWithoutCas : ChaseLevOrders {
  static constexpr std::string_view kName = "Broken:TakeLastWithoutCas";
  static constexpr Defect defects() noexcept { return Defect::kTakeLastWithoutCas; }
};

// Push publishes bottom without the release fence (B4 none): a thief that sees the new bottom need not see the
// element's payload (a data race on it) or the element itself.
struct BrokenPushWithoutRelease : ChaseLevOrders {
  static constexpr std::string_view kName = "Broken:PushWithoutRelease";
  static constexpr Fence fence(Site s) noexcept {
    return s == Site::kPushReleaseFence ? Fence::kNone : ChaseLevOrders::fence(s);
  }
};

}  // namespace frontsteal
