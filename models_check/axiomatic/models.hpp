// models.hpp — the consistency axioms of three memory models, written from the papers:
//
// RC11 (Lahav, Vafeiadis, Kang, Hur, Dreyer, "Repairing Sequential Consistency in C/C++11", PLDI 2017, §3):
//   rs   = [W] ; po|loc? ; [W ⊒ rlx] ; (rf ; rmw)*                                      release sequence
//   sw   = [E ⊒ rel] ; ([F] ; po)? ; rs ; rf ; [R ⊒ rlx] ; (po ; [F])? ; [E ⊒ acq]   synchronises-with
//   hb   = (po ∪ sw)+          eco = (rf ∪ co ∪ fr)+          (co is the paper's mo, fr its rb)
//   Coherence    hb ; eco? irreflexive
//   Atomicity    rmw ∩ (fr ; co) = ∅
//   SC           acyclic(psc_base ∪ psc_F), with
//                scb = po ∪ po|≠loc ; hb ; po|≠loc ∪ hb|loc ∪ co ∪ fr
//                psc_base = ([E^sc] ∪ [F^sc] ; hb?) ; scb ; ([E^sc] ∪ hb? ; [F^sc])
//                psc_F    = [F^sc] ; (hb ∪ hb ; eco ; hb) ; [F^sc]
//   No-thin-air  acyclic(po ∪ rf)
// "RC11 without no-thin-air" drops the last axiom: C++ as the standard words it, where load buffering (LB) is
// allowed. The initial writes are po-before every event here (they happen before the threads start).
//
// ARMv8 (Pulte, Flur, Deacon, French, Sarkar, Sewell, "Simplifying ARM Concurrency: Multicopy-atomic
// Axiomatic and Operational Models for ARMv8", POPL 2018, the axiomatic model, in the form Arm publishes it as
// herd's aarch64.cat, herdtools7 catalogue/aarch64/cats):
//   Internal     acyclic(po-loc ∪ co ∪ fr ∪ rf)
//   External     acyclic(ob), ob = (obs ∪ dob ∪ aob ∪ bob)+ with
//                obs = rfe ∪ coe ∪ fre
//                dob = addr ∪ data                                         D1
//                    ∪ ctrl ; [W]                                          D2
//                    ∪ (ctrl ∪ addr ; po) ; [ISB] ; po ; [R]               D3
//                    ∪ addr ; po ; [W]                                     D4
//                    ∪ (ctrl ∪ data) ; coi                                 D5
//                    ∪ (addr ∪ data) ; rfi                                 D6
//                aob = rmw                                                 A1
//                    ∪ [range(rmw)] ; rfi ; [A ∪ Q]                        A2
//                bob = po ; [DMB.FULL] ; po                                B1
//                    ∪ po ; [A] ; amo ; [L] ; po                           B2 (acquire-release atomic: a full barrier)
//                    ∪ [L] ; po ; [A]                                      B3
//                    ∪ [R \ NoRet] ; po ; [DMB.LD] ; po                    B4
//                    ∪ [A ∪ Q] ; po                                        B5
//                    ∪ [W] ; po ; [DMB.ST] ; po ; [W]                      B6
//                    ∪ po ; [L]                                            B7
//                    ∪ po ; [L] ; coi                                      B8
//   Atomic       rmw ∩ (fre ; coe) = ∅
// where addr, data and ctrl are the program's dependencies (program.hpp: addr_from, data_from, ctrl_from; ctrl
// runs from the read a branch tested to every event after the branch), amo is rmw (every atomic here is a single
// instruction), NoRet the reads of ST<OP> instructions, A the reads of LDAR / LDADDA(L) / SWPA(L), Q those of
// LDAPR, L the writes of STLR / LDADD(A)L / STADDL / SWP(A)L. Initial writes are in no thread: every rf, co or fr
// edge from or to one is external. Each clause can be dropped (ModelDefect), and the catalogue must notice.
//
// Each model can be planted with a defect (ModelDefect) for the validation's negative control: a checker
// counts only if the catalogue's verdicts catch a broken axiom.
#pragma once

#include <cstdint>
#include <string_view>

#include "models_check/axiomatic/execution.hpp"

namespace frontsteal::axiomatic {

enum class Model : std::uint8_t { rc11, rc11_without_nta, armv8 };

inline std::string_view name_of(Model m) {
  switch (m) {
    case Model::rc11: return "RC11";
    case Model::rc11_without_nta: return "RC11 without no-thin-air (C++ with LB)";
    case Model::armv8: return "ARMv8";
  }
  return "?";
}

enum class ModelDefect : std::uint8_t {
  none,
  rc11_eco_without_fr,        // eco = (rf ∪ co)+
  rc11_sw_without_fences,     // sw without its ([F];po)? and (po;[F])? parts
  armv8_internal_without_fr,  // acyclic(po-loc ∪ co ∪ rf)
  // One ARMv8 ordered-before clause dropped (the labels of the header).
  armv8_dob_without_addr_data,        // D1
  armv8_dob_without_ctrl_write,       // D2
  armv8_dob_without_isb,              // D3
  armv8_dob_without_addr_po_write,    // D4
  armv8_dob_without_dependency_coi,   // D5
  armv8_dob_without_dependency_rfi,   // D6
  armv8_aob_without_rmw,              // A1
  armv8_aob_without_rfi_acquire,      // A2
  armv8_bob_without_dmb_full,         // B1
  armv8_bob_without_acq_rel_amo,      // B2
  armv8_bob_without_release_acquire,  // B3
  armv8_bob_without_dmb_ld,           // B4
  armv8_bob_without_acquire,          // B5
  armv8_bob_without_dmb_st,           // B6
  armv8_bob_without_release,          // B7
  armv8_bob_without_release_coi,      // B8
};

// Why dropping this clause can change no verdict of any program this checker can express, or empty when it can.
// A1 (rmw in aob): every ob edge into an atomic's read also reaches its write. An rfe from W0 comes with coe
// W0 → write (the internal axiom puts W0 co-before the atomic's write); addr reaches both events; the ISB and
// (addr|data);rfi routes are matched by addr;po;[W] and (ctrl|data);coi; an A read is followed by [A];po; the
// barrier clauses end in po. Only exclusives (LDXR/STXR, two instructions) could tell, and these programs have none;
// tests/models_check/axiomatic/clause_search_test.cpp looks for a counterexample in the catalogue, the protocol's
// programs and random ones, and finds none (while the same search tells clauses that matter).
inline std::string_view implied_by_other_clauses(ModelDefect d) {
  return d == ModelDefect::armv8_aob_without_rmw
             ? "implied by the other clauses for single-instruction atomics (models.hpp says why); no program here "
               "can tell"
             : "";
}

namespace detail {

template <class X>
inline auto events_where(const X& x, auto&& predicate) {
  decltype(x.reads) s{};
  for (int e = 0; e < x.event_count; ++e) {
    if (predicate(x.events[e])) insert(s, e);
  }
  return s;
}

inline bool acquires(const Event& e) {
  if (e.instruction == nullptr) return false;
  const Order o = e.instruction->order;
  if (e.kind == EventKind::write) return false;
  return o == Order::acquire || o == Order::acq_rel || o == Order::seq_cst;
}
inline bool releases(const Event& e) {
  if (e.instruction == nullptr) return false;
  const Order o = e.instruction->order;
  if (e.kind == EventKind::read) return false;
  return o == Order::release || o == Order::acq_rel || o == Order::seq_cst;
}
inline bool seq_cst(const Event& e) { return e.instruction != nullptr && e.instruction->order == Order::seq_cst; }

// RC11's program order: the initial writes happen before everything a thread does.
template <class X>
inline auto rc11_po(const X& x) {
  return x.po | X::Rel::product(x.event_count, x.initial, x.all() & ~x.initial);
}

}  // namespace detail

// RC11's happens-before, hb = (po ∪ sw)+ (the header's rs and sw).
template <class X>
inline typename X::Rel rc11_happens_before(const X& x, ModelDefect defect = ModelDefect::none) {
  using Rel = typename X::Rel;
  const int n = x.event_count;
  const Rel id = Rel::identity(n, x.all());
  const Rel po = detail::rc11_po(x);
  const Rel po_loc = po & x.same_location;
  const auto rel = detail::events_where(x, detail::releases);
  const auto acq = detail::events_where(x, detail::acquires);
  const auto F = x.fences, R = x.reads, W = x.writes;
  const Rel rs = po_loc.maybe().restrict(W, W).then(x.rf.then(x.rmw).star());
  Rel sw(n);
  if (defect == ModelDefect::rc11_sw_without_fences) {
    sw = Rel::identity(n, rel).then(rs).then(x.rf).then(Rel::identity(n, R & acq));
  } else {
    const Rel fence_before = id | Rel::identity(n, F).then(po);
    const Rel fence_after = id | po.then(Rel::identity(n, F));
    sw = Rel::identity(n, rel)
             .then(fence_before)
             .then(rs)
             .then(x.rf)
             .then(Rel::identity(n, R))
             .then(fence_after)
             .then(Rel::identity(n, acq));
  }
  return (po | sw).plus();
}

// RC11, with or without no-thin-air.
template <class X>
inline bool rc11_consistent(const X& x, bool no_thin_air, ModelDefect defect = ModelDefect::none) {
  using Rel = typename X::Rel;
  const int n = x.event_count;
  const Rel po = detail::rc11_po(x);
  const Rel fr = x.fr();
  const auto sc = detail::events_where(x, detail::seq_cst);
  const auto F = x.fences;
  const Rel hb = rc11_happens_before(x, defect);
  const Rel eco = (defect == ModelDefect::rc11_eco_without_fr ? (x.rf | x.co) : (x.rf | x.co | fr)).plus();

  if (!hb.then(eco.maybe()).irreflexive()) return false;  // coherence
  if (!(x.rmw & fr.then(x.co)).empty()) return false;     // atomicity
  const Rel po_other_loc = po.minus(x.same_location);
  const Rel scb = po | po_other_loc.then(hb).then(po_other_loc) | (hb & x.same_location) | x.co | fr;
  const Rel sc_id = Rel::identity(n, sc & ~F), scf_id = Rel::identity(n, sc & F);
  const Rel psc_base = (sc_id | scf_id.then(hb.maybe())).then(scb).then(sc_id | hb.maybe().then(scf_id));
  const Rel psc_f = scf_id.then(hb | hb.then(eco).then(hb)).then(scf_id);
  if (!(psc_base | psc_f).acyclic()) return false;          // SC
  if (no_thin_air && !(po | x.rf).acyclic()) return false;  // no-thin-air
  return true;
}

// ARMv8's multicopy-atomic axiomatic model, on the instructions' ARMv8 view.
template <class X>
inline bool armv8_consistent(const X& x, ModelDefect defect = ModelDefect::none) {
  using Rel = typename X::Rel;
  const int n = x.event_count;
  const Rel& po = x.po;  // initial writes are in no thread
  const Rel po_loc = po & x.same_location;
  const Rel fr = x.fr();
  const Rel internal = x.internal(), external = x.external();

  const Rel co_internal_check =
      defect == ModelDefect::armv8_internal_without_fr ? (po_loc | x.co | x.rf) : (po_loc | x.co | fr | x.rf);
  if (!co_internal_check.acyclic()) return false;  // internal visibility

  const auto arm = [&](auto&& predicate) {
    return detail::events_where(
        x, [&](const Event& e) { return e.instruction != nullptr && predicate(*e.instruction, e); });
  };
  const auto A = arm([](const Instruction& in, const Event& e) { return e.kind == EventKind::read && in.arm.acquire; });
  const auto Q =
      arm([](const Instruction& in, const Event& e) { return e.kind == EventKind::read && in.arm.acquire_pc; });
  const auto L =
      arm([](const Instruction& in, const Event& e) { return e.kind == EventKind::write && in.arm.release; });
  const auto ordered_reads =
      arm([](const Instruction& in, const Event& e) { return e.kind == EventKind::read && !in.arm.result_unused; });
  const auto dmb_full = arm([](const Instruction& in, const Event&) { return in.arm.fence == ArmFence::full; });
  const auto dmb_ld = arm([](const Instruction& in, const Event&) { return in.arm.fence == ArmFence::load; });
  const auto dmb_st = arm([](const Instruction& in, const Event&) { return in.arm.fence == ArmFence::store; });
  const auto isb = arm([](const Instruction& in, const Event&) { return in.arm.fence == ArmFence::isb; });
  const auto W = x.writes, R = x.reads;

  const Rel obs = (x.rf & external) | (x.co & external) | (fr & external);
  const Rel coi = x.co & internal, rfi = x.rf & internal;
  const auto is = [&](const auto& s) { return Rel::identity(n, s); };
  const auto keep = [&](ModelDefect clause) { return defect != clause; };
  const Rel &addr = x.addr, &data = x.data, &ctrl = x.ctrl;

  Rel dob(n);
  if (keep(ModelDefect::armv8_dob_without_addr_data)) dob = dob | addr | data;
  if (keep(ModelDefect::armv8_dob_without_ctrl_write)) dob = dob | ctrl.then(is(W));
  if (keep(ModelDefect::armv8_dob_without_isb)) dob = dob | (ctrl | addr.then(po)).then(is(isb)).then(po).then(is(R));
  if (keep(ModelDefect::armv8_dob_without_addr_po_write)) dob = dob | addr.then(po).then(is(W));
  if (keep(ModelDefect::armv8_dob_without_dependency_coi)) dob = dob | (ctrl | data).then(coi);
  if (keep(ModelDefect::armv8_dob_without_dependency_rfi)) dob = dob | (addr | data).then(rfi);

  Rel aob(n);
  if (keep(ModelDefect::armv8_aob_without_rmw)) aob = aob | x.rmw;
  if (keep(ModelDefect::armv8_aob_without_rfi_acquire)) aob = aob | is(x.rmw.range()).then(rfi).then(is(A | Q));

  Rel bob(n);
  if (keep(ModelDefect::armv8_bob_without_dmb_full)) bob = bob | po.then(is(dmb_full)).then(po);
  if (keep(ModelDefect::armv8_bob_without_acq_rel_amo)) bob = bob | po.then(is(A)).then(x.rmw).then(is(L)).then(po);
  if (keep(ModelDefect::armv8_bob_without_release_acquire)) bob = bob | is(L).then(po).then(is(A));
  if (keep(ModelDefect::armv8_bob_without_dmb_ld)) bob = bob | is(ordered_reads).then(po).then(is(dmb_ld)).then(po);
  if (keep(ModelDefect::armv8_bob_without_acquire)) bob = bob | is(A | Q).then(po);
  if (keep(ModelDefect::armv8_bob_without_dmb_st)) bob = bob | is(W).then(po).then(is(dmb_st)).then(po).then(is(W));
  if (keep(ModelDefect::armv8_bob_without_release)) bob = bob | po.then(is(L));
  if (keep(ModelDefect::armv8_bob_without_release_coi)) bob = bob | po.then(is(L)).then(coi);
  if (!(obs | dob | aob | bob).acyclic()) return false;                        // external visibility
  if (!(x.rmw & (fr & external).then(x.co & external)).empty()) return false;  // atomic
  return true;
}

template <class X>
inline bool consistent(const X& x, Model m, ModelDefect defect = ModelDefect::none) {
  switch (m) {
    case Model::rc11: return rc11_consistent(x, true, defect);
    case Model::rc11_without_nta: return rc11_consistent(x, false, defect);
    case Model::armv8: return armv8_consistent(x, defect);
  }
  return false;
}

}  // namespace frontsteal::axiomatic
