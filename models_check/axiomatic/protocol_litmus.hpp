// protocol_litmus.hpp — the protocol's handshake as a litmus program, generated from a policy (core/policies.hpp)
// and the site table (core/site.hpp), so the program cannot drift from the code: every access's order and every
// fence come from Policy::order / Policy::fence at the site, and every instruction carries the site's label.
//
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

#include "core/policies.hpp"
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

template <class Policy>
ProtocolLitmus handshake_litmus() {
  constexpr int transient = 0, end = 1;
  const auto access = [](Op op, Site s, int loc, int value_or_reg) {
    Instruction i;
    i.op = op;
    i.location = loc;
    if (op == Op::load)
      i.reg = value_or_reg;
    else
      i.value = value_or_reg;
    i.order = order_of(Policy::order(s));
    i.label = std::string(info(s).label);
    return i;
  };
  const auto fence_at = [](Site s, std::vector<Instruction>& thread) {
    if (const std::optional<Order> o = fence_order_of(Policy::fence(s))) {
      Instruction i;
      i.op = Op::fence;
      i.order = *o;
      i.label = std::string(info(s).label);
      thread.push_back(i);
    }
  };
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

inline std::vector<ProtocolLitmus> handshake_litmus_all() {
  return {handshake_litmus<SeqCst>(), handshake_litmus<Fenced>(), handshake_litmus<Asymmetric>(),
          handshake_litmus<Minimal>(), handshake_litmus<Paper>()};
}

}  // namespace frontsteal::axiomatic
