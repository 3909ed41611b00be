// protocol_litmus.hpp — the protocol's scenarios as litmus programs, generated from a policy (core/policies.hpp)
// and the site table (core/site.hpp), so the programs cannot drift from the code: every access's order and every
// fence come from Policy::order / Policy::fence at the site, and every instruction carries the site's label.
//
// The handshake (the claim against the steal):
//     owner (claims an item)                thief (holds LockList[b], shrinks the victim's list)
//     O1  ListTransient := 1                T3  End := mid
//     F1  fence                             F2  fence
//     O2  r0 := End                         T4  r1 := ListTransient
// Final state asked: r0 = 0 ∧ r1 = 0 — the owner claims with the old End while the thief does not wait for the
// claim: both process the item (a duplicate). Exactly-once needs it forbidden. Fences: a compiler-only fence
// orders nothing in these models; Asymmetric's membarrier is modelled as a full fence on both sides at the
// thief's call (what the kernel guarantees: every running thread of the process passes a full barrier), i.e.
// a seq_cst fence at F1 and F2.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/chase_lev_policies.hpp"
#include "core/policies.hpp"
#include "core/publication_policies.hpp"
#include "core/site.hpp"
#include "models_check/axiomatic/program.hpp"

namespace frontsteal::axiomatic {

inline Order order_of(Mo mo) {
  switch (mo) {
    case Mo::kRelaxed: return Order::relaxed;
    case Mo::kAcquire: return Order::acquire;
    case Mo::kRelease: return Order::release;
    case Mo::kAcqRel: return Order::acq_rel;
    case Mo::kSeqCst: return Order::seq_cst;
  }
  return Order::seq_cst;
}

// The fence a fence site becomes, or none (no fence, or a compiler-only one).
inline std::optional<Order> fence_order_of(Fence f) {
  switch (f) {
    case Fence::kNone:
    case Fence::kCompiler: return std::nullopt;
    case Fence::kAcquire: return Order::acquire;
    case Fence::kRelease: return Order::release;
    case Fence::kAcqRel: return Order::acq_rel;
    case Fence::kSeqCst:
    case Fence::kAsymmetricLight:  // membarrier from the other side: a full barrier here (see above)
    case Fence::kAsymmetricHeavy: return Order::seq_cst;
  }
  return Order::seq_cst;
}

struct ProtocolLitmus {
  std::string policy;
  Contract contract;
  LitmusTest test;
};

// An access at a protocol site, in the policy's order, labelled with the site. `reg` receives what a load or a
// read-modify-write reads (−1: unused); `value` is what a store or exchange writes, or a fetch_add's operand.
template <class Policy>
Instruction site_access(Op op, Site s, int location, int value, int reg) {
  Instruction i;
  i.op = op;
  i.location = location;
  i.value = value;
  i.reg = reg;
  i.order = order_of(Policy::order(s));
  i.label = std::string(info(s).label);
  return i;
}

// The fence the policy puts at fence site `s`, appended to `thread` (nothing for no fence or a compiler fence).
template <class Policy>
void push_site_fence(Site s, std::vector<Instruction>& thread) {
  if (const std::optional<Order> o = fence_order_of(Policy::fence(s))) {
    Instruction i;
    i.op = Op::fence;
    i.order = *o;
    i.label = std::string(info(s).label);
    thread.push_back(i);
  }
}

template <class Policy>
ProtocolLitmus handshake_litmus() {
  constexpr int transient = 0, end = 1;
  const auto access = [](Op op, Site s, int loc, int value_or_reg) {
    return op == Op::load ? site_access<Policy>(op, s, loc, 0, value_or_reg)
                          : site_access<Policy>(op, s, loc, value_or_reg, -1);
  };
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  LitmusTest t;
  t.name = "handshake (" + std::string(Policy::kName) + ")";
  t.locations = {"ListTransient", "End"};
  t.registers = {"owner.e", "thief.t"};
  std::vector<Instruction> owner{access(Op::store, Site::kOwnerAnnounce, transient, 1)};
  fence_at(Site::kOwnerStoreLoadFence, owner);
  owner.push_back(access(Op::load, Site::kOwnerReadEnd, end, 0));
  std::vector<Instruction> thief{access(Op::store, Site::kThiefShrinkEnd, end, 1)};
  fence_at(Site::kThiefStoreLoadFence, thief);
  thief.push_back(access(Op::load, Site::kThiefAwaitTransient, transient, 1));
  t.threads = {owner, thief};
  t.final_state = {{{0, 0}, {1, 0}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// The thief's re-read (stealing_protocol.hpp's try_steal after T4): the victim claims its last item with the
// old End while the thief lowers End; the thief waits until ListTransient is 0 and re-reads Front to skip what
// the victim claimed.
//     owner (Front = 1, claims item 1)     thief (holds LockList, mid = 1)
//     O1  ListTransient := 1               T3  End := 1
//     F1  fence                            F2  fence
//     O2  r0 := End                        T4  r1 := ListTransient
//     (r0 = 2 > Front: after a branch:)    T5  r2 := Front
//     O3  Front := 2
//     O4  ListTransient := 0
// Initially ListTransient = 0, End = 2, Front = 1. Asked: r0 = 2 ∧ r1 = 0 ∧ r2 = 1 — the owner claimed item 1
// with the old End, and the thief, past its wait, still read Front = 1, so it keeps item 1 too (a duplicate).
// T4 reading the initial 0 is the handshake's case (F1/F2); T4 reading O4's 0 is this path's: O4 must publish
// O3 to T5 (O4 release, T4 acquire). T4 is a spin loop in the code; its exiting iteration is the load here.
template <class Policy>
ProtocolLitmus reread_litmus() {
  constexpr int transient = 0, end = 1, front = 2;
  const auto at = site_access<Policy>;
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  std::vector<Instruction> owner{at(Op::store, Site::kOwnerAnnounce, transient, 1, -1)};
  fence_at(Site::kOwnerStoreLoadFence, owner);
  const int read_end = static_cast<int>(owner.size());
  owner.push_back(at(Op::load, Site::kOwnerReadEnd, end, 0, 0));
  Instruction claim = at(Op::store, Site::kOwnerClaimFront, front, 2, -1);
  claim.ctrl_from = read_end;  // `if (f >= end)`: the branch on O2
  owner.push_back(claim);
  Instruction retract = at(Op::store, Site::kOwnerRetract, transient, 0, -1);
  retract.ctrl_from = read_end;
  owner.push_back(retract);
  std::vector<Instruction> thief{at(Op::store, Site::kThiefShrinkEnd, end, 1, -1)};
  fence_at(Site::kThiefStoreLoadFence, thief);
  thief.push_back(at(Op::load, Site::kThiefAwaitTransient, transient, 0, 1));
  thief.push_back(at(Op::load, Site::kThiefRereadFront, front, 0, 2));
  LitmusTest t;
  t.name = "re-read after the wait (" + std::string(Policy::kName) + ")";
  t.locations = {"ListTransient", "End", "Front"};
  t.registers = {"owner.e", "thief.t", "thief.front"};
  t.threads = {owner, thief};
  t.initial = {0, 2, 1};
  t.final_state = {{{0, 2}, {1, 0}, {2, 1}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// Termination (active_workers.hpp, stealing_protocol.hpp's shrink_victim and try_claim): the path on which an idle
// worker could stop looking for work while a stolen share is held by nobody it counts.
//     thief                        victim (owner of the list)           idle worker
//     A1  Active += 1              O1  ListTransient := 1               A3  r1 := Active
//     T3  End := mid               F1  fence
//     F2  fence                    O2  r0 := End
//     T4  ListTransient?           (r0 = mid: the list is exhausted, so, after a branch on r0:)
//                                  O4  ListTransient := 0
//                                  A2  Active -= 1
// Initially Active = 1 (the victim), End = 2 (one item left: index 1; the victim's Front is 1), mid = 1. Asked:
// r0 = 1 ∧ r1 = 0 — the victim saw the steal and left, and the idle worker read 0: an early quit (the
// thief's share still runs, exactly once; the idle worker just stops helping). SC forbids it: A1 precedes T3,
// which precedes O2 and so A2, so the count never passes through 0.
template <class Policy>
ProtocolLitmus termination_litmus() {
  constexpr int transient = 0, end = 1, active = 2;
  const auto at = site_access<Policy>;
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  std::vector<Instruction> thief{at(Op::fetch_add, Site::kActiveJoin, active, +1, -1),
                                 at(Op::store, Site::kThiefShrinkEnd, end, 1, -1)};
  fence_at(Site::kThiefStoreLoadFence, thief);
  thief.push_back(at(Op::load, Site::kThiefAwaitTransient, transient, 0, 2));
  std::vector<Instruction> victim{at(Op::store, Site::kOwnerAnnounce, transient, 1, -1)};
  fence_at(Site::kOwnerStoreLoadFence, victim);
  const int read_end = static_cast<int>(victim.size());
  victim.push_back(at(Op::load, Site::kOwnerReadEnd, end, 0, 0));
  Instruction retract = at(Op::store, Site::kOwnerRetract, transient, 0, -1);
  retract.ctrl_from = read_end;  // `if (f >= end)`: the branch on O2
  victim.push_back(retract);
  victim.push_back(at(Op::fetch_add, Site::kActiveLeave, active, -1, -1));
  std::vector<Instruction> idle{at(Op::load, Site::kActivePoll, active, 0, 1)};
  LitmusTest t;
  t.name = "termination (" + std::string(Policy::kName) + ")";
  t.locations = {"ListTransient", "End", "Active"};
  t.registers = {"victim.e", "idle.active", "thief.t"};
  t.threads = {thief, victim, idle};
  t.initial = {0, 2, 1};
  t.final_state = {{{0, 1}, {1, 0}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// Minimal as Relacy alone derives it: T3 and O2 relaxed (Relacy never produces load buffering, so it cannot see
// why they are needed). The termination path's negative control: under C++ with load buffering and on ARMv8 an
// idle worker quits early; core/policies.hpp's Minimal orders T3 release and O2 acquire for that reason.
struct MinimalRelacyDerived : Minimal {
  static constexpr std::string_view kName = "Minimal as Relacy derives it (T3, O2 relaxed)";
  static constexpr Mo order(Site s) noexcept {
    if (s == Site::kThiefShrinkEnd || s == Site::kOwnerReadEnd) return Mo::kRelaxed;
    return Minimal::order(s);
  }
};

inline std::vector<ProtocolLitmus> termination_litmus_all() {
  return {termination_litmus<SeqCst>(),  termination_litmus<Fenced>(), termination_litmus<Asymmetric>(),
          termination_litmus<Minimal>(), termination_litmus<Paper>(),  termination_litmus<MinimalRelacyDerived>()};
}

// Publication (component_publication.hpp, greedy rendering): a component of two surfaces written by two
// tessellators; the one whose W1 count-down is the last publishes the back slot (W2); the pusher reads the
// published slot (P2) and then the triangles.
//     tessellator A              tessellator B                          pusher
//     triangles A := 1           triangles B := 1                       P2  r0 := Published
//     W1  r2 := Done += 1        W1  r3 := Done += 1                    r1 := triangles A
//                                (r3 = 1: last, so after a branch:)
//                                W2  Published := slot 1 (exchange)
// Asked: r3 = 1 ∧ r0 = 1 ∧ r1 = 0 — the pusher draws the published component without tessellator A's triangles
// (a torn component). The triangle writes are plain in the code; here they are relaxed atomics, which is what
// a race-free program's plain accesses may be treated as for this question.
template <class Policy>
ProtocolLitmus publication_litmus() {
  constexpr int triangles_a = 0, triangles_b = 1, done = 2, published = 3;
  const auto at = site_access<Policy>;
  const auto plain = [](Op op, int loc, int value, int reg) {
    Instruction i;
    i.op = op;
    i.location = loc;
    i.value = value;
    i.reg = reg;
    i.label = "triangles";
    return i;
  };
  std::vector<Instruction> a{plain(Op::store, triangles_a, 1, -1),
                             at(Op::fetch_add, Site::kWriterCountDown, done, 1, 2)};
  std::vector<Instruction> b{plain(Op::store, triangles_b, 1, -1),
                             at(Op::fetch_add, Site::kWriterCountDown, done, 1, 3)};
  Instruction publish = at(Op::exchange, Site::kWriterPublish, published, 1, 4);
  publish.ctrl_from = 1;  // `if (before + 1 == done_target)`
  b.push_back(publish);
  std::vector<Instruction> pusher{at(Op::load, Site::kPusherReadPublished, published, 0, 0),
                                  plain(Op::load, triangles_a, 0, 1)};
  LitmusTest t;
  t.name = "publication (" + std::string(Policy::kName) + ")";
  t.locations = {"TrianglesA", "TrianglesB", "Done", "Published"};
  t.registers = {"pusher.slot", "pusher.triangles_a", "a.before", "b.before", "b.retired"};
  t.threads = {a, b, pusher};
  t.final_state = {{{3, 1}, {0, 1}, {1, 0}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// Two thieves of one victim, serialized by LockList (try_lock.hpp): the first holds the lock, shrinks End and
// releases; the second takes the lock and reads End to size its share.
//     thief 1 (holds LockList)          thief 2
//     T3  End := 1                      L2  r0 := exchange(LockList, 1)
//     L3  LockList := 0                 T2  r1 := End
// Initially LockList = 1, End = 2. Asked: r0 = 0 ∧ r1 = 2 — the second thief got the lock from the first and
// still sized its share by the old End: both would steal [1, 2) (a duplicate).
template <class Policy>
ProtocolLitmus lock_litmus() {
  constexpr int lock = 0, end = 1;
  const auto at = site_access<Policy>;
  LitmusTest t;
  t.name = "steal under the lock (" + std::string(Policy::kName) + ")";
  t.locations = {"LockList", "End"};
  t.registers = {"thief2.lock", "thief2.end"};
  t.threads = {{at(Op::store, Site::kThiefShrinkEnd, end, 1, -1), at(Op::store, Site::kLockRelease, lock, 0, -1)},
               {at(Op::exchange, Site::kLockAcquire, lock, 1, 0), at(Op::load, Site::kThiefReadEnd, end, 0, 1)}};
  t.initial = {1, 2};
  t.final_state = {{{0, 0}, {1, 2}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// Reclamation (component_publication.hpp): the last tessellator publishes a new slot and reads which update the
// pusher has started; the pusher announces its update and reads the published slot. A store→load pattern on
// each side.
//     last tessellator                           pusher
//     W2  r0 := exchange(Published, 2)           P1  Started := 1
//     W3  r1 := Started                          P2  r2 := Published
// Initially Published = 1 (the slot now retired). Asked: r0 = 1 ∧ r1 = 0 ∧ r2 = 1 — the tessellator believes no
// update has started since the retirement (it may hand slot 1 out again once the older updates complete), while
// update 1 draws from slot 1: a use after reuse.
template <class Policy>
ProtocolLitmus reclamation_litmus() {
  constexpr int published = 0, started = 1;
  const auto at = site_access<Policy>;
  LitmusTest t;
  t.name = "reclamation (" + std::string(Policy::kName) + ")";
  t.locations = {"Published", "Started"};
  t.registers = {"writer.retired", "writer.started", "pusher.slot"};
  t.threads = {
      {at(Op::exchange, Site::kWriterPublish, published, 2, 0), at(Op::load, Site::kWriterReadStarted, started, 0, 1)},
      {at(Op::store, Site::kPusherAnnounce, started, 1, -1),
       at(Op::load, Site::kPusherReadPublished, published, 0, 2)}};
  t.initial = {1, 0};
  t.final_state = {{{0, 1}, {1, 0}, {2, 1}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// The Chase–Lev deque's take against a steal (chase_lev_deque.hpp), two elements (top = 0, bottom = 2): a first
// thief has read top = 0 and claims index 0 (S5); the owner takes from the bottom; a second thief reads top,
// then bottom, and claims index 1.
//     owner                       thief 1                  thief 2
//     K2  bottom := 1             S5  cas(top, 0 → 1)      S1  r1 := top
//     K3  fence                                            S2  fence
//     K4  r0 := top                                        S3  r2 := bottom
//                                                          S5  cas(top, 1 → 2)
// Asked: r0 = 0 ∧ r1 = 1 ∧ r2 = 2 — the owner saw top = 0 < 1, so it takes index 1 without a CAS, while the
// second thief saw top = 1 < bottom = 2 and claims index 1 too: one element returned twice.
template <class Policy>
ProtocolLitmus chase_lev_litmus() {
  constexpr int top = 0, bottom = 1;
  const auto at = site_access<Policy>;
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  const auto cas = [&](int expected, int desired) {
    Instruction i = at(Op::cas, Site::kStealClaim, top, desired, -1);
    i.expected = expected;
    return i;
  };
  std::vector<Instruction> owner{at(Op::store, Site::kTakeReserveBottom, bottom, 1, -1)};
  fence_at(Site::kTakeFence, owner);
  owner.push_back(at(Op::load, Site::kTakeReadTop, top, 0, 0));
  std::vector<Instruction> thief2{at(Op::load, Site::kStealReadTop, top, 0, 1)};
  fence_at(Site::kStealFence, thief2);
  thief2.push_back(at(Op::load, Site::kStealReadBottom, bottom, 0, 2));
  thief2.push_back(cas(1, 2));
  LitmusTest t;
  t.name = "Chase-Lev take/steal (" + std::string(Policy::kName) + ")";
  t.locations = {"top", "bottom"};
  t.registers = {"owner.t", "thief2.t", "thief2.b"};
  t.threads = {owner, {cas(0, 1)}, thief2};
  t.initial = {0, 2};
  t.final_state = {{{0, 0}, {1, 1}, {2, 2}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// The Chase–Lev deque's push against a steal (chase_lev_deque.hpp), an empty deque (top = bottom = 0): the owner
// pushes one element; a thief reads top, then bottom, and reads the element's slot.
//     owner                       thief
//     B3  buffer[0] := 1          S1  r0 := top
//     B4  release fence           S2  fence
//     B5  bottom := 1             S3  r1 := bottom
//                                 (r1 > r0: after a branch:)
//                                 S4  r2 := buffer[0]
// Asked: r1 = 1 ∧ r2 = 0 — the thief sees the push's bottom but not its element (it would steal garbage).
template <class Policy>
ProtocolLitmus chase_lev_push_litmus() {
  constexpr int top = 0, bottom = 1, buffer = 2;
  const auto at = site_access<Policy>;
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  std::vector<Instruction> owner{at(Op::store, Site::kPushWriteSlot, buffer, 1, -1)};
  fence_at(Site::kPushReleaseFence, owner);
  owner.push_back(at(Op::store, Site::kPushPublishBottom, bottom, 1, -1));
  std::vector<Instruction> thief{at(Op::load, Site::kStealReadTop, top, 0, 0)};
  fence_at(Site::kStealFence, thief);
  const int read_bottom = static_cast<int>(thief.size());
  thief.push_back(at(Op::load, Site::kStealReadBottom, bottom, 0, 1));
  Instruction read_slot = at(Op::load, Site::kStealReadSlot, buffer, 0, 2);
  read_slot.ctrl_from = read_bottom;  // `if (t < b)`
  thief.push_back(read_slot);
  LitmusTest t;
  t.name = "Chase-Lev push/steal (" + std::string(Policy::kName) + ")";
  t.locations = {"top", "bottom", "buffer[0]"};
  t.registers = {"thief.t", "thief.b", "thief.x"};
  t.threads = {owner, thief};
  t.final_state = {{{1, 1}, {2, 0}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

// The race for the last element (one element: top = 0, bottom = 1): the owner's take reserves it and, seeing
// top = bottom - 1, claims it by a CAS on top (K6); a thief read top and the old bottom and claims it by its
// own CAS (S5).
//     owner                           thief
//     K2  bottom := 0                 S1  r1 := top
//     K3  fence                       S2  fence
//     K4  r0 := top                   S3  r2 := bottom
//     (r0 = 0 = b − 1:) K6 cas(top, 0 → 1)    (r2 > r1:) S5 cas(top, 0 → 1)
// Asked: r0 = 0 ∧ r1 = 0 ∧ r2 = 1 with both claims succeeding (each CAS is modelled on its success path): the
// element returned twice. Only the CASes' atomicity forbids it; Broken:TakeLastWithoutCas (no K6) reaches it.
template <class Policy>
ProtocolLitmus chase_lev_last_litmus() {
  constexpr int top = 0, bottom = 1;
  const auto at = site_access<Policy>;
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) { push_site_fence<Policy>(s, thread); };
  const auto cas = [&](Site s, int ctrl) {
    Instruction i = at(Op::cas, s, top, 1, -1);
    i.expected = 0;
    i.ctrl_from = ctrl;
    return i;
  };
  std::vector<Instruction> owner{at(Op::store, Site::kTakeReserveBottom, bottom, 0, -1)};
  fence_at(Site::kTakeFence, owner);
  const int read_top = static_cast<int>(owner.size());
  owner.push_back(at(Op::load, Site::kTakeReadTop, top, 0, 0));
  if (!has(Policy::defects(), Defect::kTakeLastWithoutCas)) owner.push_back(cas(Site::kTakeClaimLast, read_top));
  std::vector<Instruction> thief{at(Op::load, Site::kStealReadTop, top, 0, 1)};
  fence_at(Site::kStealFence, thief);
  const int read_bottom = static_cast<int>(thief.size());
  thief.push_back(at(Op::load, Site::kStealReadBottom, bottom, 0, 2));
  thief.push_back(cas(Site::kStealClaim, read_bottom));
  LitmusTest t;
  t.name = "Chase-Lev last element (" + std::string(Policy::kName) + ")";
  t.locations = {"top", "bottom"};
  t.registers = {"owner.t", "thief.t", "thief.b"};
  t.threads = {owner, thief};
  t.initial = {0, 1};
  t.final_state = {{{0, 0}, {1, 0}, {2, 1}}, {}};
  return {std::string(Policy::kName), Policy::kContract, t};
}

inline std::vector<ProtocolLitmus> chase_lev_push_litmus_all() {
  return {chase_lev_push_litmus<ChaseLevOrders>(), chase_lev_push_litmus<BrokenPushWithoutRelease>()};
}

inline std::vector<ProtocolLitmus> chase_lev_last_litmus_all() {
  return {chase_lev_last_litmus<ChaseLevOrders>(), chase_lev_last_litmus<BrokenTakeLastWithoutCas>()};
}

inline std::vector<ProtocolLitmus> chase_lev_litmus_all() {
  return {chase_lev_litmus<ChaseLevOrders>(), chase_lev_litmus<BrokenTakeWithoutFence>()};
}

inline std::vector<ProtocolLitmus> lock_litmus_all() {
  return {lock_litmus<SeqCst>(), lock_litmus<Fenced>(), lock_litmus<Asymmetric>(), lock_litmus<Minimal>(),
          lock_litmus<Paper>()};
}

inline std::vector<ProtocolLitmus> reclamation_litmus_all() { return {reclamation_litmus<PublicationOrders>()}; }

inline std::vector<ProtocolLitmus> publication_litmus_all() { return {publication_litmus<PublicationOrders>()}; }

inline std::vector<ProtocolLitmus> reread_litmus_all() {
  return {reread_litmus<SeqCst>(), reread_litmus<Fenced>(), reread_litmus<Asymmetric>(), reread_litmus<Minimal>(),
          reread_litmus<Paper>()};
}

inline std::vector<ProtocolLitmus> handshake_litmus_all() {
  return {handshake_litmus<SeqCst>(), handshake_litmus<Fenced>(), handshake_litmus<Asymmetric>(),
          handshake_litmus<Minimal>(), handshake_litmus<Paper>()};
}

}  // namespace frontsteal::axiomatic
