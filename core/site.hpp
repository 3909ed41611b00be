// site.hpp — every shared-memory access site of the protocol, named and labelled.
//
// A memory-order policy (policies.hpp) assigns an order to each Site; a backend receives the Site with
// every operation so it can inject chaos there (stress/) or name it in a trace (models_check/). The labels
// (O1, F1, T3, ...) are the ones used in the opening comment of stealing_protocol.hpp (and of
// component_publication.hpp and chase_lev_deque.hpp for their protocols), in mutation-testing
// output and in failure reports. Adding a site means adding a row to kSiteTable.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace frontsteal {

enum class Site : std::uint8_t {
  // Owner's claim of one item (paper §4.2.1 lines 1-2 with §4.2.2's ListTransient).
  kOwnerAnnounce,        // O1  ListTransient[p] := 1
  kOwnerStoreLoadFence,  // F1  orders O1 before O2 (the owner half of the Dekker handshake)
  kOwnerReadEnd,         // O2  read the end of ActivityList[p]
  kOwnerClaimFront,      // O3  Front[p] := f + 1
  kOwnerRetract,         // O4  ListTransient[p] := 0
  // Thief's steal from victim b (§4.2.2 lines 651-654).
  kThiefReadFront,       // T1  first read of Front[b], sizes the share
  kThiefReadEnd,         // T2  read of End[b] (protected by LockList[b])
  kThiefShrinkEnd,       // T3  End[b] := mid, the linearization point of a steal
  kThiefStoreLoadFence,  // F2  orders T3 before T4 (the thief half of the Dekker handshake)
  kThiefAwaitTransient,  // T4  busy-wait until ListTransient[b] == 0
  kThiefRereadFront,     // T5  re-read Front[b]: everything below it is the victim's
  // LockList[b], the non-blocking try-lock that serializes thieves (and a worker installing its own list).
  kLockProbe,    // L1  cheap look before the exchange
  kLockAcquire,  // L2  exchange 0 -> 1
  kLockRelease,  // L3  store 0
  // A worker installing a new list into its own slot, under its own LockList.
  kInstallFront,  // I1  Front[p] := 0
  kInstallEnd,    // I2  End[p] := item count of the new list
  // Termination detection: the number of workers that hold, or are taking, unfinished work.
  kActiveJoin,   // A1  a thief about to shrink a non-empty victim list: +1
  kActiveLeave,  // A2  a worker whose list is exhausted: -1
  kActivePoll,   // A3  an idle worker looks for 0: the frame's work is done
  // Frame boundary: persistent workers between frames.
  kFrameStart,        // E1  caller publishes the next frame number
  kFrameAwaitStart,   // E2  worker waits for it
  kFrameArrive,       // E3  worker counts itself done with the frame
  kFrameResetActive,  // E4  last arriver re-arms the active count for the next frame
  kFramePublishDone,  // E5  last arriver publishes the frame as done
  kFrameAwaitDone,    // E6  caller (and workers before the next frame) wait for it
  // Greedy rendering's publication of per-component triangles (component_publication.hpp, paper §5.2).
  kPusherAnnounce,       // P1  pusher: Started := u before reading any component
  kPusherReadPublished,  // P2  pusher: read Published[c], once per component and update
  kPusherComplete,       // P3  pusher: Completed := u after drawing every component
  kWriterCountDown,      // W1  tessellator: Remaining[c] -= 1 after writing one surface's triangles
  kWriterPublish,        // W2  last tessellator of c: Published[c] := back slot (the atomic swap)
  kWriterReadStarted,    // W3  same tessellator: read Started, the retired slot's reclamation stamp
  kDriverReadCompleted,  // D1  frame driver: read Completed to see which retired slots are free
  // The Chase–Lev deque (chase_lev_deque.hpp). Labels B (push: the Bottom end), K (taKe), S (Steal), H (size
  // Hint); Lê et al.'s own labels (P1-P4, T1-T5, S1-S5) collide with the publication and stealing protocols,
  // so the deque's opening comment maps each of ours to theirs.
  kPushReadBottom,     // B1  owner: read its own bottom
  kPushReadTop,        // B2  owner: read top to check for room (Lê et al. P1)
  kPushWriteSlot,      // B3  owner: buffer[b] := x (P2)
  kPushReleaseFence,   // B4  release fence between B3 and B5 (P3)
  kPushPublishBottom,  // B5  bottom := b + 1, the linearization point of push (P4)
  kTakeReadBottom,     // K1  owner: read its own bottom (T1)
  kTakeReserveBottom,  // K2  bottom := b - 1, reserving the element below (T2)
  kTakeFence,          // K3  seq_cst fence between K2 and K4 (T3)
  kTakeReadTop,        // K4  read top (T4)
  kTakeReadSlot,       // K5  read buffer[b]
  kTakeClaimLast,      // K6  CAS top t -> t + 1 for the last element (T5)
  kTakeRestoreEmpty,   // K7  bottom := b + 1 after finding the deque empty
  kTakeRestoreLast,    // K8  bottom := b + 1 after the race for the last element
  kStealReadTop,       // S1  thief: read top
  kStealFence,         // S2  seq_cst fence between S1 and S3
  kStealReadBottom,    // S3  read bottom
  kStealReadSlot,      // S4  read buffer[t] (before the CAS: afterwards the slot may be reused)
  kStealClaim,         // S5  CAS top t -> t + 1, the linearization point of a successful steal
  kHintReadBottom,     // H1  size_hint: read bottom (statistics and tests only)
  kHintReadTop,        // H2  size_hint: read top
  kCount
};

inline constexpr std::size_t kSiteCount = static_cast<std::size_t>(Site::kCount);

enum class SiteKind : std::uint8_t { kLoad, kStore, kReadModifyWrite, kFence };

// Which protocol a site belongs to: the stealing protocol (stealing_protocol.hpp, frame_loop.hpp) or greedy
// rendering's triangle publication (component_publication.hpp), or the Chase–Lev deque of the baseline
// scheduler (chase_lev_deque.hpp). Mutation testing weakens one protocol's sites at a time; a policy of one
// protocol never meets the other's sites.
enum class Protocol : std::uint8_t { kStealing, kPublication, kChaseLev };

struct SiteInfo {
  Site site;
  std::string_view label;  // short label used in comments and reports, e.g. "O1"
  std::string_view name;   // dotted name, e.g. "owner.announce"
  SiteKind kind;
  std::string_view what;  // one line: what the access does
  Protocol protocol = Protocol::kStealing;
};

inline constexpr std::array<SiteInfo, kSiteCount> kSiteTable{{
    {Site::kOwnerAnnounce, "O1", "owner.announce", SiteKind::kStore,
     "ListTransient[p] := 1 before reading the list end"},
    {Site::kOwnerStoreLoadFence, "F1", "owner.storeload_fence", SiteKind::kFence, "StoreLoad between O1 and O2"},
    {Site::kOwnerReadEnd, "O2", "owner.read_end", SiteKind::kLoad, "read End[p] to decide whether Front is claimable"},
    {Site::kOwnerClaimFront, "O3", "owner.claim_front", SiteKind::kStore, "Front[p] := f + 1, claiming item f"},
    {Site::kOwnerRetract, "O4", "owner.retract", SiteKind::kStore, "ListTransient[p] := 0 after updating Front"},
    {Site::kThiefReadFront, "T1", "thief.read_front", SiteKind::kLoad, "first read of Front[b] to size the share"},
    {Site::kThiefReadEnd, "T2", "thief.read_end", SiteKind::kLoad, "read End[b] under LockList[b]"},
    {Site::kThiefShrinkEnd, "T3", "thief.shrink_end", SiteKind::kStore, "End[b] := mid, taking the second half"},
    {Site::kThiefStoreLoadFence, "F2", "thief.storeload_fence", SiteKind::kFence, "StoreLoad between T3 and T4"},
    {Site::kThiefAwaitTransient, "T4", "thief.await_transient", SiteKind::kLoad, "spin until ListTransient[b] == 0"},
    {Site::kThiefRereadFront, "T5", "thief.reread_front", SiteKind::kLoad, "re-read Front[b]; skip the items below it"},
    {Site::kLockProbe, "L1", "lock.probe", SiteKind::kLoad, "look at LockList before trying to take it"},
    {Site::kLockAcquire, "L2", "lock.acquire", SiteKind::kReadModifyWrite, "exchange LockList 0 -> 1"},
    {Site::kLockRelease, "L3", "lock.release", SiteKind::kStore, "LockList := 0"},
    {Site::kInstallFront, "I1", "install.front", SiteKind::kStore, "Front[p] := 0 for a newly installed list"},
    {Site::kInstallEnd, "I2", "install.end", SiteKind::kStore, "End[p] := size of the newly installed list"},
    {Site::kActiveJoin, "A1", "active.join", SiteKind::kReadModifyWrite, "active += 1 before taking work"},
    {Site::kActiveLeave, "A2", "active.leave", SiteKind::kReadModifyWrite, "active -= 1 when a list is exhausted"},
    {Site::kActivePoll, "A3", "active.poll", SiteKind::kLoad, "idle worker reads active; 0 ends the frame"},
    {Site::kFrameStart, "E1", "frame.start", SiteKind::kStore, "caller publishes frame k"},
    {Site::kFrameAwaitStart, "E2", "frame.await_start", SiteKind::kLoad, "worker waits for frame k"},
    {Site::kFrameArrive, "E3", "frame.arrive", SiteKind::kReadModifyWrite, "worker counts itself done"},
    {Site::kFrameResetActive, "E4", "frame.reset_active", SiteKind::kStore, "last arriver re-arms active := P"},
    {Site::kFramePublishDone, "E5", "frame.publish_done", SiteKind::kStore, "last arriver publishes frame k done"},
    {Site::kFrameAwaitDone, "E6", "frame.await_done", SiteKind::kLoad, "wait until frame k is done"},
    {Site::kPusherAnnounce, "P1", "pusher.announce", SiteKind::kStore, "Started := u before reading components",
     Protocol::kPublication},
    {Site::kPusherReadPublished, "P2", "pusher.read_published", SiteKind::kLoad, "read Published[c] once per update",
     Protocol::kPublication},
    {Site::kPusherComplete, "P3", "pusher.complete", SiteKind::kStore, "Completed := u after drawing",
     Protocol::kPublication},
    {Site::kWriterCountDown, "W1", "writer.count_down", SiteKind::kReadModifyWrite,
     "Remaining[c] -= 1 after a surface's triangles are written", Protocol::kPublication},
    {Site::kWriterPublish, "W2", "writer.publish", SiteKind::kReadModifyWrite,
     "Published[c] := back slot, returning the retired slot", Protocol::kPublication},
    {Site::kWriterReadStarted, "W3", "writer.read_started", SiteKind::kLoad,
     "read Started: the retired slot's reclamation stamp", Protocol::kPublication},
    {Site::kDriverReadCompleted, "D1", "driver.read_completed", SiteKind::kLoad,
     "read Completed: retired slots stamped at or below it are free", Protocol::kPublication},
    {Site::kPushReadBottom, "B1", "push.read_bottom", SiteKind::kLoad, "owner reads its own bottom",
     Protocol::kChaseLev},
    {Site::kPushReadTop, "B2", "push.read_top", SiteKind::kLoad, "read top: is there room for one more element",
     Protocol::kChaseLev},
    {Site::kPushWriteSlot, "B3", "push.write_slot", SiteKind::kStore, "buffer[b] := x", Protocol::kChaseLev},
    {Site::kPushReleaseFence, "B4", "push.release_fence", SiteKind::kFence, "orders B3 before B5", Protocol::kChaseLev},
    {Site::kPushPublishBottom, "B5", "push.publish_bottom", SiteKind::kStore,
     "bottom := b + 1: the element is stealable", Protocol::kChaseLev},
    {Site::kTakeReadBottom, "K1", "take.read_bottom", SiteKind::kLoad, "owner reads its own bottom",
     Protocol::kChaseLev},
    {Site::kTakeReserveBottom, "K2", "take.reserve_bottom", SiteKind::kStore, "bottom := b - 1 before looking at top",
     Protocol::kChaseLev},
    {Site::kTakeFence, "K3", "take.storeload_fence", SiteKind::kFence, "StoreLoad between K2 and K4",
     Protocol::kChaseLev},
    {Site::kTakeReadTop, "K4", "take.read_top", SiteKind::kLoad, "read top: empty, many, or the last element",
     Protocol::kChaseLev},
    {Site::kTakeReadSlot, "K5", "take.read_slot", SiteKind::kLoad, "read buffer[b]", Protocol::kChaseLev},
    {Site::kTakeClaimLast, "K6", "take.claim_last", SiteKind::kReadModifyWrite,
     "CAS top t -> t + 1: race thieves for the last element", Protocol::kChaseLev},
    {Site::kTakeRestoreEmpty, "K7", "take.restore_empty", SiteKind::kStore, "bottom := b + 1: the deque was empty",
     Protocol::kChaseLev},
    {Site::kTakeRestoreLast, "K8", "take.restore_last", SiteKind::kStore, "bottom := b + 1 after the last-element race",
     Protocol::kChaseLev},
    {Site::kStealReadTop, "S1", "steal.read_top", SiteKind::kLoad, "thief reads top", Protocol::kChaseLev},
    {Site::kStealFence, "S2", "steal.storeload_fence", SiteKind::kFence,
     "orders S1 before S3 in the total order of fences", Protocol::kChaseLev},
    {Site::kStealReadBottom, "S3", "steal.read_bottom", SiteKind::kLoad, "read bottom: is there an element at top",
     Protocol::kChaseLev},
    {Site::kStealReadSlot, "S4", "steal.read_slot", SiteKind::kLoad, "read buffer[t] before claiming it",
     Protocol::kChaseLev},
    {Site::kStealClaim, "S5", "steal.claim", SiteKind::kReadModifyWrite, "CAS top t -> t + 1: the steal",
     Protocol::kChaseLev},
    {Site::kHintReadBottom, "H1", "hint.read_bottom", SiteKind::kLoad, "size_hint reads bottom (racy, statistics only)",
     Protocol::kChaseLev},
    {Site::kHintReadTop, "H2", "hint.read_top", SiteKind::kLoad, "size_hint reads top (racy, statistics only)",
     Protocol::kChaseLev},
}};

constexpr const SiteInfo& info(Site s) noexcept { return kSiteTable[static_cast<std::size_t>(s)]; }

// The table is indexed by Site: a row out of place is a compile error, not a mislabelled report.
constexpr bool site_table_is_ordered() {
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    if (static_cast<std::size_t>(kSiteTable[i].site) != i) return false;
  }
  return true;
}
static_assert(site_table_is_ordered(), "kSiteTable rows must follow the order of enum Site");

}  // namespace frontsteal
