// policies.hpp — memory-order policies: the order of every labelled access site, and each policy's contract.
//
// A policy is a type with:
//   kName, kContract (exactly-once or at-least-once), kNeedsMembarrier, and constexpr-or-runtime functions
//   order(Site) -> Mo, fence(Site) -> Fence and defects() -> Defect (deliberate bugs, negative controls only).
// models_check/ uses a runtime table policy so one binary can run every policy and every mutant.
// The protocol asks the policy at every access; with the constexpr policies below the answer folds into the
// instruction, so a policy costs exactly its fences.
//
// The handshake these policies differ on (labels from site.hpp):
//     owner                               thief (holds LockList[b])
//     O1  ListTransient := 1              T3  End := mid
//     F1  fence                           F2  fence
//     O2  e := End                        T4  t := ListTransient
// This is store buffering (Dekker). Both threads may read the other's old value unless F1 and F2 together
// forbid it. If O2 reads the old End while T4 reads the old ListTransient, the owner claims an item of the
// thief's share and the thief does not wait for that claim, so both process it: a duplicate, never a loss.
//
//   SeqCst      every site seq_cst (fences included, though with all four handshake accesses seq_cst they
//               are redundant; models_check/ shows which). Exactly-once.
//   Paper       the paper's handshake as written: acquire/release, no StoreLoad fence. AT-LEAST-ONCE: on
//               x86 (store buffer) and under the C++ model the store-buffering outcome above is allowed, so
//               an item can run twice (never zero times). Paper §4.2.2 assumes sequential consistency.
//   Fenced      acquire/release plus one seq_cst fence on each side of the handshake (F1, F2). Exactly-once.
//   Minimal     the weakest orders the model checker certifies (see below). Exactly-once.
//   Asymmetric  the owner's F1 is only a compiler barrier; the thief's F2 is membarrier(PRIVATE_EXPEDITED),
//               which runs a full barrier on every CPU running this process. Exactly-once when the kernel
//               supports it (registration is checked at start, see membarrier.hpp); the owner pays nothing.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "core/memory_order.hpp"
#include "core/site.hpp"

namespace frontsteal {

enum class Contract : std::uint8_t { kExactlyOnce, kAtLeastOnce };

constexpr std::string_view name(Contract c) noexcept {
  return c == Contract::kExactlyOnce ? "exactly-once" : "at-least-once";
}

// Deliberate protocol defects. Only negative controls (negative_controls.hpp) set these, so tests and
// checkers can prove they are able to fail. One bit each, 32 bits wide so the next negative control has room;
// every defect is declared once in kDefectTable with the primitive (Protocol, site.hpp) it breaks.
enum class Defect : std::uint32_t {
  kNone = 0,
  kSkipFrontReread = 1u << 0,      // thief keeps its whole share without re-reading Front (drops T4, T5)
  kOwnerSkipsTransient = 1u << 1,  // owner claims without raising ListTransient (drops O1, O4)
  kReuseWithoutGrace = 1u << 2,    // the frame driver reuses a retired slot without waiting for the pusher
  kPublishEachSurface = 1u << 3,   // every surface swaps its component in (no per-component count: torn)
  kThiefJoinsLate = 1u << 4,       // thief joins the active count after lowering End (A1 after T3)
  kTakeLastWithoutCas = 1u << 5,   // the owner keeps the last element without racing thieves for it (no K6)
  kShareLowerBound = 1u << 6,      // every copied entry starts at mid, not at max(mid, entry start)
  kOwnerNeverRetracts = 1u << 7,   // owner raises ListTransient (O1) but never lowers it: a hang, for watchdogs
  kBatchIgnoresEnd = 1u << 8,      // a batched claim is bounded by its entry, not by the End it read at O2
};

struct DefectInfo {
  Defect defect;
  std::string_view name;  // as reports and checkers print it
  Protocol protocol;      // the primitive whose sites it breaks
};

inline constexpr std::array<DefectInfo, 9> kDefectTable{{
    {Defect::kSkipFrontReread, "skip_front_reread", Protocol::kStealing},
    {Defect::kOwnerSkipsTransient, "owner_skips_transient", Protocol::kStealing},
    {Defect::kReuseWithoutGrace, "reuse_without_grace", Protocol::kPublication},
    {Defect::kPublishEachSurface, "publish_each_surface", Protocol::kPublication},
    {Defect::kThiefJoinsLate, "thief_joins_late", Protocol::kStealing},
    {Defect::kTakeLastWithoutCas, "take_last_without_cas", Protocol::kChaseLev},
    {Defect::kShareLowerBound, "share_lower_bound", Protocol::kStealing},
    {Defect::kOwnerNeverRetracts, "owner_never_retracts", Protocol::kStealing},
    {Defect::kBatchIgnoresEnd, "batch_ignores_end", Protocol::kStealing},
}};

constexpr Defect operator|(Defect a, Defect b) noexcept {
  return static_cast<Defect>(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr bool has(Defect set, Defect d) noexcept {
  return (static_cast<std::uint32_t>(set) & static_cast<std::uint32_t>(d)) != 0;
}

// The rows of kDefectTable are single, distinct bits: two defects sharing a bit would plant both at once.
constexpr bool defect_table_is_one_bit_each() {
  std::uint32_t seen = 0;
  for (const DefectInfo& d : kDefectTable) {
    const auto bit = static_cast<std::uint32_t>(d.defect);
    if (bit == 0 || (bit & (bit - 1)) != 0 || (seen & bit) != 0) return false;
    seen |= bit;
  }
  return true;
}
static_assert(defect_table_is_one_bit_each(), "every Defect is one bit of its own");

// The primitive a (single) defect breaks; kStealing for kNone.
constexpr Protocol protocol_of(Defect d) noexcept {
  for (const DefectInfo& row : kDefectTable) {
    if (row.defect == d) return row.protocol;
  }
  return Protocol::kStealing;
}

// The order an access of a given kind gets under plain acquire/release labelling: loads acquire, stores
// release, read-modify-writes both.
constexpr Mo acquire_release_order(Site s) noexcept {
  switch (info(s).kind) {
    case SiteKind::kLoad: return Mo::kAcquire;
    case SiteKind::kStore: return Mo::kRelease;
    case SiteKind::kReadModifyWrite: return Mo::kAcqRel;
    case SiteKind::kFence: break;
  }
  return Mo::kRelaxed;  // unreachable for access sites; fences use fence()
}

struct SeqCst {
  static constexpr std::string_view kName = "SeqCst";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site) noexcept { return Mo::kSeqCst; }
  static constexpr Fence fence(Site) noexcept { return Fence::kSeqCst; }
};

struct Paper {
  static constexpr std::string_view kName = "Paper";
  static constexpr Contract kContract = Contract::kAtLeastOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site s) noexcept { return acquire_release_order(s); }
  static constexpr Fence fence(Site) noexcept { return Fence::kNone; }
};

struct Fenced {
  static constexpr std::string_view kName = "Fenced";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site s) noexcept { return acquire_release_order(s); }
  static constexpr Fence fence(Site s) noexcept {
    return (s == Site::kOwnerStoreLoadFence || s == Site::kThiefStoreLoadFence) ? Fence::kSeqCst : Fence::kNone;
  }
};

struct Asymmetric {
  static constexpr std::string_view kName = "Asymmetric";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = true;
  static constexpr Mo order(Site s) noexcept { return acquire_release_order(s); }
  static constexpr Fence fence(Site s) noexcept {
    if (s == Site::kOwnerStoreLoadFence) return Fence::kAsymmetricLight;
    if (s == Site::kThiefStoreLoadFence) return Fence::kAsymmetricHeavy;
    return Fence::kNone;
  }
};

// Minimal: the weakest orders under which every model-checking scenario passes. Derived by
// `frontsteal-modelcheck --derive-minimal Fenced` (greedy one-step weakening while every scenario passes) and
// certified on every CI run: each one-step weakening of it is killed by some Relacy scenario, or — for the two
// orders Relacy cannot see, because it never produces load buffering — by the axiomatic checker under C++ with
// load buffering (models_check/minimal_survivors.hpp, results/models_check/). "Weakest" means no single site can
// be weakened one step, not a global optimum, and it rests on bounded searches. Why each non-relaxed site is
// needed:
//   F1, F2 seq_cst   the Dekker handshake (O1 before O2, T3 before T4): without either, Paper's duplicate
//   O4 release / T4 acquire   publish the owner's Front (O3) to the thief's re-read (T5)
//   T3 release / O2 acquire   the thief's join (A1) happens-before the leave (A2) of a victim that sees its
//                    steal: without them, under C++ with load buffering (and on ARMv8 without T3's release) the
//                    victim's leave may come first, the count touches 0 while the share is uncounted, and an
//                    idle worker quits early (exactly-once still holds). On x86 both are plain moves.
//   L2 acquire / L3 release   the LockList protects End and the list body between thieves and installs
//   E1 release, E3 acq_rel, E5 release, E6 acquire   frame boundaries order item effects across frames and
//                    towards the caller
//   E2 acquire       a worker takes over its per-frame fields (stats, lists) only after the caller is done
//                    reading them. (An earlier derivation relaxed E2: those fields were invisible to Relacy
//                    until frame_loop.hpp's `handover` cell stood for them; ThreadSanitizer found the race.)
// The termination count (A1-A3) itself is relaxed: it decides only when idle workers stop looking for work, T3
// and O2 order it where that matters, and every item is still ordered before the frame's end by E3.
struct Minimal {
  static constexpr std::string_view kName = "Minimal";
  static constexpr Contract kContract = Contract::kExactlyOnce;
  static constexpr Defect defects() noexcept { return Defect::kNone; }
  static constexpr bool kNeedsMembarrier = false;
  static constexpr Mo order(Site s) noexcept {
    switch (s) {
      case Site::kOwnerRetract:
      case Site::kThiefShrinkEnd:
      case Site::kLockRelease:
      case Site::kFrameStart:
      case Site::kFramePublishDone: return Mo::kRelease;
      case Site::kOwnerReadEnd:
      case Site::kThiefAwaitTransient:
      case Site::kLockAcquire:
      case Site::kFrameAwaitStart:
      case Site::kFrameAwaitDone: return Mo::kAcquire;
      case Site::kFrameArrive: return Mo::kAcqRel;
      default: return Mo::kRelaxed;
    }
  }
  static constexpr Fence fence(Site s) noexcept {
    return (s == Site::kOwnerStoreLoadFence || s == Site::kThiefStoreLoadFence) ? Fence::kSeqCst : Fence::kNone;
  }
};

// Whether a policy's orders forbid the store-buffering outcome of the handshake, read off its table:
// both sides order their store before their load, by a seq_cst fence, by seq_cst accesses, or by the
// asymmetric pair (heavy on the thief side, at least a compiler barrier on the owner side).
// This is the static half of the story; models_check/ and stress/ check it dynamically.
template <class Policy>
constexpr bool forbids_store_buffering() {
  const Fence f1 = Policy::fence(Site::kOwnerStoreLoadFence);
  const Fence f2 = Policy::fence(Site::kThiefStoreLoadFence);
  const bool owner_seq = f1 == Fence::kSeqCst || (Policy::order(Site::kOwnerAnnounce) == Mo::kSeqCst &&
                                                  Policy::order(Site::kOwnerReadEnd) == Mo::kSeqCst);
  const bool thief_seq = f2 == Fence::kSeqCst || (Policy::order(Site::kThiefShrinkEnd) == Mo::kSeqCst &&
                                                  Policy::order(Site::kThiefAwaitTransient) == Mo::kSeqCst);
  const bool asymmetric = f2 == Fence::kAsymmetricHeavy && f1 != Fence::kNone;
  return (owner_seq && thief_seq) || asymmetric;
}

static_assert(forbids_store_buffering<SeqCst>());
static_assert(!forbids_store_buffering<Paper>());
static_assert(forbids_store_buffering<Fenced>());
static_assert(forbids_store_buffering<Asymmetric>());
static_assert(forbids_store_buffering<Minimal>());

}  // namespace frontsteal
