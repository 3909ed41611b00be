// litmus_catalogue.cpp — the validation tests (see the header). The AArch64 programs are written from herd's
// catalogue files (herdtools7, catalogue/aarch64/tests and catalogue/aarch64-readers-guide/tests, *.litmus) and
// their verdicts from their kinds.txt; the tutorial's and the C++ ones from the papers and issue reports named in
// each entry's source.
#include "models_check/axiomatic/litmus_catalogue.hpp"

#include <utility>

namespace frontsteal::axiomatic {
namespace {

constexpr int x = 0, y = 1, z = 2, w = 3;

// AArch64 instructions.
Instruction LDR(int loc, int reg) {
  Instruction i;
  i.op = Op::load;
  i.location = loc;
  i.reg = reg;
  return i;
}
Instruction LDAR(int loc, int reg) {
  Instruction i = LDR(loc, reg);
  i.arm.acquire = true;
  return i;
}
Instruction LDAPR(int loc, int reg) {
  Instruction i = LDR(loc, reg);
  i.arm.acquire_pc = true;
  return i;
}
Instruction STR(int loc, int value) {
  Instruction i;
  i.op = Op::store;
  i.location = loc;
  i.value = value;
  return i;
}
Instruction STLR(int loc, int value) {
  Instruction i = STR(loc, value);
  i.arm.release = true;
  return i;
}
Instruction DMB(ArmFence f) {
  Instruction i;
  i.op = Op::fence;
  i.arm.fence = f;
  return i;
}
// LDADD{A}{L} (reg ≥ 0) or STADD{L} (reg < 0: the result goes to the zero register).
Instruction LDADD(int loc, int operand, int reg, bool acquire = false, bool release = false) {
  Instruction i;
  i.op = Op::fetch_add;
  i.location = loc;
  i.value = operand;
  i.reg = reg;
  i.arm.acquire = acquire && reg >= 0;  // an acquire whose result is discarded is no acquire (ARM ARM)
  i.arm.release = release;
  i.arm.result_unused = reg < 0;
  return i;
}
// SWP{A}{L}: writes `value`, reads the old one into `reg` (reg < 0: the zero register).
Instruction SWP(int loc, int value, int reg, bool acquire = false, bool release = false) {
  Instruction i = LDADD(loc, value, reg, acquire, release);
  i.op = Op::exchange;
  return i;
}

Instruction ISB() { return DMB(ArmFence::isb); }
// A compare-and-swap on its success path: reads `expected`, writes `value` (CAS{A}{L}; reg < 0: CAS WZR, the
// result discarded, so the read is NoRet and an acquire no acquire, as for LDADD).
Instruction CAS(int loc, int expected, int value, int reg, bool acquire = false, bool release = false) {
  Instruction i = LDADD(loc, value, reg, acquire, release);
  i.op = Op::cas;
  i.expected = expected;
  return i;
}
// Dependencies on what the instruction at index `from` of the same thread read (program.hpp). Register-only
// instructions (EOR, ADD, CMP, CSEL, MOV) are not instructions here; each test says which dependency they leave.
Instruction with_addr(Instruction i, int from) {
  i.addr_from = from;
  return i;
}
Instruction with_data(Instruction i, int from) {
  i.data_from = from;
  return i;
}
Instruction with_ctrl(Instruction i, int from) {
  i.ctrl_from = from;
  return i;
}

// C++ accesses.
Instruction load(int loc, int reg, Order o) {
  Instruction i = LDR(loc, reg);
  i.order = o;
  return i;
}
Instruction store(int loc, int value, Order o) {
  Instruction i = STR(loc, value);
  i.order = o;
  return i;
}
Instruction fence(Order o) {
  Instruction i;
  i.op = Op::fence;
  i.order = o;
  return i;
}
Instruction fetch_add(int loc, int operand, int reg, Order o) {
  Instruction i;
  i.op = Op::fetch_add;
  i.location = loc;
  i.value = operand;
  i.reg = reg;
  i.order = o;
  return i;
}

LitmusTest make(std::string name, std::vector<std::vector<Instruction>> threads, FinalState final_state) {
  LitmusTest t;
  t.name = std::move(name);
  int regs = 0, locations = 2;
  for (const auto& thread : threads) {
    for (const Instruction& in : thread) {
      regs = std::max(regs, in.reg + 1);
      locations = std::max(locations, in.location + 1);
    }
  }
  static const char* const kNames[] = {"x", "y", "z", "w"};
  t.locations.assign(kNames, kNames + locations);
  for (int r = 0; r < regs; ++r) t.registers.push_back("r" + std::to_string(r));
  t.threads = std::move(threads);
  t.final_state = std::move(final_state);
  return t;
}

constexpr std::optional<bool> kAllowed = true, kForbidden = false, kNotAsked = std::nullopt;

CatalogueEntry aarch64(LitmusTest t, bool allowed) {
  return {std::move(t), false, "herd AArch64 catalogue (kinds.txt)", {kNotAsked, kNotAsked, allowed}};
}
CatalogueEntry readers_guide(LitmusTest t, bool allowed) {
  return {std::move(t), false, "herd AArch64 readers' guide catalogue (kinds.txt)", {kNotAsked, kNotAsked, allowed}};
}
CatalogueEntry tutorial(LitmusTest t, bool allowed) {
  return {std::move(t),
          false,
          "Maranget, Sarkar, Sewell, A Tutorial Introduction to the ARM and POWER Relaxed Memory Models (2012); "
          "the same verdict under ARMv8 (Pulte et al., POPL 2018)",
          {kNotAsked, kNotAsked, allowed}};
}
// No published test isolates these clauses; the verdict is derived by hand from the clause's text in Arm's
// aarch64.cat, so the entry shows that the checker has the clause, not that the clause is right.
CatalogueEntry from_model_text(LitmusTest t, bool allowed, const std::string& clause) {
  return {std::move(t),
          false,
          "derived by hand from aarch64.cat's " + clause + " (not an independent verdict)",
          {kNotAsked, kNotAsked, allowed}};
}
CatalogueEntry cpp(LitmusTest t, std::string source, std::optional<bool> rc11, std::optional<bool> rc11_lb,
                   std::optional<bool> armv8) {
  return {std::move(t), true, std::move(source), {rc11, rc11_lb, armv8}};
}

const auto dmb_sy = [] { return DMB(ArmFence::full); };
const auto dmb_ld = [] { return DMB(ArmFence::load); };

}  // namespace

std::vector<CatalogueEntry> litmus_catalogue() {
  std::vector<CatalogueEntry> c;
  // --- AArch64, herd's catalogue ---------------------------------------------------------------------------
  // SB: exists 0:X0=0 ∧ 1:X0=0 (registers r0, r1 here).
  const FinalState sb_final{{{0, 0}, {1, 0}}, {}};
  c.push_back(aarch64(make("SB", {{STR(x, 1), LDR(y, 0)}, {STR(y, 1), LDR(x, 1)}}, sb_final), true));
  c.push_back(
      aarch64(make("SB+dmb.sy+po", {{STR(x, 1), dmb_sy(), LDR(y, 0)}, {STR(y, 1), LDR(x, 1)}}, sb_final), true));
  c.push_back(aarch64(
      make("SB+dmb.sys", {{STR(x, 1), dmb_sy(), LDR(y, 0)}, {STR(y, 1), dmb_sy(), LDR(x, 1)}}, sb_final), false));
  c.push_back(aarch64(make("SB+dmb.sy+rel-acq", {{STR(x, 1), dmb_sy(), LDR(y, 0)}, {STLR(y, 1), LDAR(x, 1)}}, sb_final),
                      false));
  c.push_back(aarch64(
      make("SB+dmb.sy+rel-acqpc", {{STR(x, 1), dmb_sy(), LDR(y, 0)}, {STLR(y, 1), LDAPR(x, 1)}}, sb_final), true));
  // MP: exists 1:X0=1 ∧ 1:X2=0.
  const FinalState mp_final{{{0, 1}, {1, 0}}, {}};
  c.push_back(aarch64(make("MP", {{STR(x, 1), STR(y, 1)}, {LDR(y, 0), LDR(x, 1)}}, mp_final), true));
  c.push_back(
      aarch64(make("MP+dmb.sy+po", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {LDR(y, 0), LDR(x, 1)}}, mp_final), true));
  c.push_back(
      aarch64(make("MP+po+dmb.sy", {{STR(x, 1), STR(y, 1)}, {LDR(y, 0), dmb_sy(), LDR(x, 1)}}, mp_final), true));
  c.push_back(aarch64(
      make("MP+dmb.sys", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {LDR(y, 0), dmb_sy(), LDR(x, 1)}}, mp_final), false));
  c.push_back(aarch64(make("MP+rel+acq", {{STR(x, 1), STLR(y, 1)}, {LDAR(y, 0), LDR(x, 1)}}, mp_final), false));
  c.push_back(aarch64(make("MP+rel+acqpc", {{STR(x, 1), STLR(y, 1)}, {LDAPR(y, 0), LDR(x, 1)}}, mp_final), false));
  // LB: exists 0:X0=1 ∧ 1:X0=1.
  const FinalState lb_final{{{0, 1}, {1, 1}}, {}};
  c.push_back(aarch64(make("LB", {{LDR(x, 0), STR(y, 1)}, {LDR(y, 1), STR(x, 1)}}, lb_final), true));
  c.push_back(
      aarch64(make("LB+dmb.sy+po", {{LDR(x, 0), dmb_sy(), STR(y, 1)}, {LDR(y, 1), STR(x, 1)}}, lb_final), true));
  c.push_back(aarch64(
      make("LB+dmb.sys", {{LDR(x, 0), dmb_sy(), STR(y, 1)}, {LDR(y, 1), dmb_sy(), STR(x, 1)}}, lb_final), false));
  // LB with an atomic add whose amount depends on the read (ORR w, w, #1: a data dependency, value 1 here):
  // exists 1:X5=1 ∧ 0:X0=1. The second thread's add has a used (LDADD) or discarded (STADD) result.
  {
    Instruction add = LDADD(y, 1, 2);
    add.data_from = 0;
    c.push_back(
        aarch64(make("LB+rel+LDADD", {{LDR(y, 0), STLR(x, 1)}, {LDR(x, 1), add}}, {{{1, 1}, {0, 1}}, {}}), false));
    Instruction stadd = LDADD(y, 1, -1);
    stadd.data_from = 0;
    c.push_back(
        aarch64(make("LB+rel+STADD", {{LDR(y, 0), STLR(x, 1)}, {LDR(x, 1), stadd}}, {{{1, 1}, {0, 1}}, {}}), false));
  }
  // 2+2W: exists x=2 ∧ y=2.
  const FinalState ww_final{{}, {{x, 2}, {y, 2}}};
  c.push_back(aarch64(make("2+2W", {{STR(x, 2), STR(y, 1)}, {STR(y, 2), STR(x, 1)}}, ww_final), true));
  c.push_back(
      aarch64(make("2+2W+dmb.sy+po", {{STR(x, 2), dmb_sy(), STR(y, 1)}, {STR(y, 2), STR(x, 1)}}, ww_final), true));
  c.push_back(aarch64(
      make("2+2W+dmb.sys", {{STR(x, 2), dmb_sy(), STR(y, 1)}, {STR(y, 2), dmb_sy(), STR(x, 1)}}, ww_final), false));
  // R: exists y=2 ∧ 1:X2=0.
  const FinalState r_final{{{0, 0}}, {{y, 2}}};
  c.push_back(aarch64(make("R", {{STR(x, 1), STR(y, 1)}, {STR(y, 2), LDR(x, 0)}}, r_final), true));
  c.push_back(aarch64(make("R+dmb.sy+po", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {STR(y, 2), LDR(x, 0)}}, r_final), true));
  c.push_back(aarch64(make("R+po+dmb.sy", {{STR(x, 1), STR(y, 1)}, {STR(y, 2), dmb_sy(), LDR(x, 0)}}, r_final), true));
  c.push_back(
      aarch64(make("R+dmb.sys", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {STR(y, 2), dmb_sy(), LDR(x, 0)}}, r_final), false));
  // S: exists x=2 ∧ 1:X0=1.
  const FinalState s_final{{{0, 1}}, {{x, 2}}};
  c.push_back(aarch64(make("S", {{STR(x, 2), STR(y, 1)}, {LDR(y, 0), STR(x, 1)}}, s_final), true));
  c.push_back(aarch64(make("S+dmb.sy+po", {{STR(x, 2), dmb_sy(), STR(y, 1)}, {LDR(y, 0), STR(x, 1)}}, s_final), true));
  c.push_back(aarch64(make("S+po+dmb.sy", {{STR(x, 2), STR(y, 1)}, {LDR(y, 0), dmb_sy(), STR(x, 1)}}, s_final), true));
  c.push_back(
      aarch64(make("S+dmb.sys", {{STR(x, 2), dmb_sy(), STR(y, 1)}, {LDR(y, 0), dmb_sy(), STR(x, 1)}}, s_final), false));
  // Coherence.
  c.push_back(aarch64(make("CoRR", {{STR(x, 1)}, {LDR(x, 0), LDR(x, 1)}}, {{{0, 1}, {1, 0}}, {}}), false));
  c.push_back(aarch64(make("CoRW1", {{LDR(x, 0), STR(x, 1)}}, {{{0, 1}}, {}}), false));
  c.push_back(aarch64(make("CoRW2", {{STR(x, 1)}, {LDR(x, 0), STR(x, 2)}}, {{{0, 1}}, {{x, 1}}}), false));
  c.push_back(aarch64(make("CoWR", {{STR(x, 1), LDR(x, 0)}}, {{{0, 0}}, {}}), false));
  c.push_back(aarch64(make("CoWW", {{STR(x, 1), STR(x, 2)}}, {{}, {{x, 1}}}), false));
  // MP through an atomic read-modify-write of the flag: exists y=2 ∧ 1:X0=0 (the RMW read P0's 1). A discarded
  // result (…noret: destination WZR) takes the RMW's read out of DMB LD's reach and the acquire away.
  const FinalState rmw_final{{{0, 0}}, {{y, 2}}};
  c.push_back(aarch64(
      make("MP+rel+LDADD-dmb.ld", {{STR(x, 1), STLR(y, 1)}, {LDADD(y, 1, 1), dmb_ld(), LDR(x, 0)}}, rmw_final), false));
  c.push_back(aarch64(
      make("MP+rel+LDADDnoret-dmb.ld", {{STR(x, 1), STLR(y, 1)}, {LDADD(y, 1, -1), dmb_ld(), LDR(x, 0)}}, rmw_final),
      true));
  c.push_back(aarch64(
      make("MP+rel+SWP-dmb.ld", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, 1), dmb_ld(), LDR(x, 0)}}, rmw_final), false));
  c.push_back(aarch64(
      make("MP+rel+SWPnoret-dmb.ld", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, -1), dmb_ld(), LDR(x, 0)}}, rmw_final),
      true));
  c.push_back(
      aarch64(make("MP+rel+SWPacq", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, 1, true), LDR(x, 0)}}, rmw_final), false));
  c.push_back(aarch64(
      make("MP+rel+SWPacq-noret", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, -1, true), LDR(x, 0)}}, rmw_final), true));
  // MP where the reader swaps the flag, then reads it again with acquire (own write, rfi): exists 1:X2=1 ∧
  // 1:X0=0 (X2: the swap's old value). …rmw-lrs-acq adds a register-only EOR that changes nothing here.
  const FinalState swp_final{{{1, 1}, {0, 0}}, {}};
  c.push_back(aarch64(
      make("MP+rel+swp-acq", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, 1), LDAR(y, 2), LDR(x, 0)}}, swp_final), false));
  c.push_back(aarch64(
      make("MP+rel+swp-acqpc", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, 1), LDAPR(y, 2), LDR(x, 0)}}, swp_final), false));
  c.push_back(aarch64(
      make("MP+rel+rmw-lrs-acq", {{STR(x, 1), STLR(y, 1)}, {SWP(y, 2, 1), LDAR(y, 2), LDR(x, 0)}}, swp_final), false));

  // Dependencies, kinds.txt. LB+rel+… (P0: read x, STLR y; P1: read y, then a store to x of 7 or of the value
  // read): exists 0:X0=v ∧ 1:X3=1. The branches and conditional selects of P1 are resolved on the path the final
  // state takes, and each test keeps the dependency that path leaves: B.EQ on a loaded register orders every later
  // store (ctrl); a CMP of a register no load wrote leaves none; CSEL and MOV pass a dependency on only through the
  // operand they select (herd's verdicts for LB+rel+CSEL and MP+rel+CSEL).
  c.push_back(
      aarch64(make("LB+BEQ4", {{LDR(y, 0), STLR(x, 1)}, {LDR(x, 1), with_ctrl(STR(y, 1), 0)}}, lb_final), false));
  c.push_back(aarch64(make("LB+CSEL4", {{LDR(y, 0), STLR(x, 1)}, {LDR(x, 1), STR(y, 1)}}, lb_final), true));
  const FinalState lb7_final{{{0, 7}, {1, 1}}, {}};
  c.push_back(aarch64(make("LB+rel+BEQ", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), STR(x, 7)}}, lb7_final), true));
  c.push_back(
      aarch64(make("LB+rel+BEQ2", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), with_data(STR(x, 1), 0)}}, lb_final), false));
  c.push_back(aarch64(make("LB+rel+BEQ3", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), STR(x, 7)}}, lb7_final), true));
  c.push_back(aarch64(make("LB+rel+CSEL", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), STR(x, 7)}}, lb7_final), true));
  c.push_back(aarch64(make("LB+rel+CSEL2", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), STR(x, 7)}}, lb7_final), true));
  c.push_back(aarch64(make("LB+rel+CSEL3", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), STR(x, 7)}}, lb7_final), true));
  // STR W2,[X3],#4 (post-index: the base register changes after the store; the stored value depends on the read).
  c.push_back(aarch64(
      make("LB+rel+data-post", {{LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), with_data(STR(x, 1), 0)}}, lb_final), false));
  // P1 compares a constant with the loaded flag and selects between two zeros for the address offset: no
  // dependency reaches the read of x. exists 1:X0=1 ∧ 1:X6=0.
  c.push_back(aarch64(make("MP+rel+CSEL", {{STR(x, 1), STLR(y, 1)}, {LDR(y, 0), LDR(x, 1)}}, mp_final), true));
  c.push_back(
      aarch64(make("LB+dmb.sy+data-amo.swp",
                   {{LDR(x, 0), with_data(SWP(y, 1, 1), 0)}, {LDR(y, 2), dmb_sy(), STR(x, 1)}}, {{{0, 1}, {2, 1}}, {}}),
              false));
  // P0 swaps z with a value computed from x (data into the swap's write); P1 stores to y a value computed from
  // what the swap read (data from the swap's read). exists 0:X0=1 ∧ 1:X0=1.
  c.push_back(aarch64(
      make("LB+SWP-RsRt-addr+rel",
           {{LDR(x, 0), with_data(SWP(z, 1, 2), 0), with_data(STR(y, 1), 1)}, {LDR(y, 1), STLR(x, 1)}}, lb_final),
      true));
  // MP+rel+… with a local round trip through z (P1: read y, write z, read z, read x): exists 1:X2=1 ∧ 1:X0=0.
  const FinalState mp3_final{{{0, 1}, {2, 0}}, {}};
  c.push_back(
      aarch64(make("MP+rel+addr-lrs-acq",
                   {{STR(x, 1), STLR(y, 1)}, {LDR(y, 0), with_addr(STR(z, 1), 0), LDAR(z, 1), LDR(x, 2)}}, mp3_final),
              false));
  c.push_back(
      aarch64(make("MP+rel+data-lrs-acq",
                   {{STR(x, 1), STLR(y, 1)}, {LDR(y, 0), with_data(STR(z, 1), 0), LDAR(z, 1), LDR(x, 2)}}, mp3_final),
              false));
  c.push_back(
      aarch64(make("MP+rel+ctrl-lrs-acq",
                   {{STR(x, 1), STLR(y, 1)}, {LDR(y, 0), with_ctrl(STR(z, 1), 0), LDAR(z, 1), LDR(x, 2)}}, mp3_final),
              true));
  c.push_back(
      aarch64(make("MP+rel+addr-po-loc-addr",
                   {{STR(x, 1), STLR(y, 1)}, {LDR(y, 0), with_addr(LDR(z, 1), 0), LDR(z, 2), with_addr(LDR(x, 3), 2)}},
                   {{{0, 1}, {3, 0}}, {}}),
              true));
  // CAS on its success path with a constant expected value (y starts at 2; P0's STLR writes 0; the CAS swaps
  // 0 for 1): exists y=1 ∧ 1:X0=0.
  {
    const auto mp_cas = [&](const char* name, Instruction cas, bool dmb, bool allowed) {
      std::vector<Instruction> reader{cas};
      if (dmb) reader.push_back(dmb_ld());
      reader.push_back(LDR(x, 0));
      LitmusTest t = make(name, {{STR(x, 1), STLR(y, 0)}, reader}, {{{0, 0}}, {{y, 1}}});
      t.initial = {0, 2};
      c.push_back(aarch64(t, allowed));
    };
    mp_cas("MP+rel+CAS-ok-dmb.ld", CAS(y, 0, 1, 1), true, false);
    mp_cas("MP+rel+CASnoret-ok-dmb.ld", CAS(y, 0, 1, -1), true, true);
    mp_cas("MP+rel+CASacq-noret-ok", CAS(y, 0, 1, -1, true), false, true);
    mp_cas("MP+rel+CASacq-ok", CAS(y, 0, 1, 1, true), false, false);
  }

  // --- AArch64, herd's readers' guide catalogue ------------------------------------------------------------
  c.push_back(readers_guide(
      make("WRC", {{STR(x, 1)}, {LDR(x, 0), STR(y, 1)}, {LDR(y, 1), LDR(x, 2)}}, {{{0, 1}, {1, 1}, {2, 0}}, {}}),
      true));
  c.push_back(
      readers_guide(make("WRC+rel+addr", {{STR(x, 1)}, {LDR(x, 0), STLR(y, 1)}, {LDR(y, 1), with_addr(LDR(x, 2), 0)}},
                         {{{0, 1}, {1, 1}, {2, 0}}, {}}),
                    false));
  c.push_back(readers_guide(
      make("WWC", {{STR(x, 2)}, {LDR(x, 0), STR(y, 1)}, {LDR(y, 1), STR(x, 1)}}, {{{0, 2}, {1, 1}}, {{x, 2}}}), true));
  c.push_back(readers_guide(make("ISA2", {{STR(x, 1), STR(y, 1)}, {LDR(y, 0), STR(z, 1)}, {LDR(z, 1), LDR(x, 2)}},
                                 {{{0, 1}, {1, 1}, {2, 0}}, {}}),
                            true));
  const FinalState iriw_arm{{{0, 1}, {1, 0}, {2, 1}, {3, 0}}, {}};
  c.push_back(readers_guide(
      make("IRIW", {{STR(x, 1)}, {LDR(x, 0), LDR(y, 1)}, {STR(y, 1)}, {LDR(y, 2), LDR(x, 3)}}, iriw_arm), true));
  c.push_back(readers_guide(
      make("IRIW+dmb.lds",
           {{STR(x, 1)}, {LDR(x, 0), dmb_ld(), LDR(y, 1)}, {STR(y, 1)}, {LDR(y, 2), dmb_ld(), LDR(x, 3)}}, iriw_arm),
      false));
  c.push_back(
      readers_guide(make("SB+rfi-dmb.ld+rfi-dmb.ld",
                         {{STR(x, 1), LDR(x, 0), dmb_ld(), LDR(y, 1)}, {STR(y, 1), LDR(y, 2), dmb_ld(), LDR(x, 3)}},
                         {{{0, 1}, {1, 0}, {2, 1}, {3, 0}}, {}}),
                    true));
  // Read-after-dependency through z (P1: read y, then z with an address dependency, z again, then x with one):
  // RSW allows it; RDW, where another thread writes z between P1's two reads, forbids it.
  const std::vector<Instruction> rsw_reader{LDR(y, 0), with_addr(LDR(z, 1), 0), LDR(z, 2), with_addr(LDR(x, 3), 2)};
  c.push_back(readers_guide(make("RSW", {{STR(x, 1), STLR(y, 1)}, rsw_reader}, {{{0, 1}, {3, 0}}, {}}), true));
  c.push_back(readers_guide(
      make("RDW", {{STR(x, 1), STLR(y, 1)}, rsw_reader, {STR(z, 1)}}, {{{0, 1}, {1, 0}, {2, 1}, {3, 0}}, {}}), false));
  // PPO… and MP+popl+ctrl-rfi-addr: P1 reads y, writes z with a dependency (A addr, C ctrl, D data), reads z
  // back, then reads x with a dependency on that read: exists 1:X0=1 ∧ 1:X5=1 ∧ 1:X7=0. With P0's plain stores
  // every one is allowed; with a release, a ctrl dependency into the local round trip still orders nothing.
  {
    const FinalState ppo_final{{{0, 1}, {1, 1}, {2, 0}}, {}};
    const auto ppo = [&](const char* name, Instruction store_z, Instruction read_x, bool release) {
      return make(name, {{STR(x, 1), release ? STLR(y, 1) : STR(y, 1)}, {LDR(y, 0), store_z, LDR(z, 1), read_x}},
                  ppo_final);
    };
    c.push_back(readers_guide(ppo("PPOAA", with_addr(STR(z, 1), 0), with_addr(LDR(x, 2), 2), false), true));
    c.push_back(readers_guide(ppo("PPOAC", with_addr(STR(z, 1), 0), with_ctrl(LDR(x, 2), 2), false), true));
    c.push_back(readers_guide(ppo("PPOCA", with_ctrl(STR(z, 1), 0), with_addr(LDR(x, 2), 2), false), true));
    c.push_back(readers_guide(ppo("PPOCC", with_ctrl(STR(z, 1), 0), with_ctrl(LDR(x, 2), 2), false), true));
    c.push_back(readers_guide(ppo("PPODA", with_data(STR(z, 1), 0), with_addr(LDR(x, 2), 2), false), true));
    c.push_back(readers_guide(ppo("PPODC", with_data(STR(z, 1), 0), with_ctrl(LDR(x, 2), 2), false), true));
    c.push_back(
        readers_guide(ppo("MP+popl+ctrl-rfi-addr", with_ctrl(STR(z, 1), 0), with_addr(LDR(x, 2), 2), true), true));
  }

  // --- AArch64, the tutorial's dependency tests ------------------------------------------------------------
  c.push_back(tutorial(
      make("MP+dmb.sy+addr", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {LDR(y, 0), with_addr(LDR(x, 1), 0)}}, mp_final),
      false));
  c.push_back(tutorial(
      make("MP+dmb.sy+ctrl", {{STR(x, 1), dmb_sy(), STR(y, 1)}, {LDR(y, 0), with_ctrl(LDR(x, 1), 0)}}, mp_final),
      true));
  c.push_back(tutorial(make("MP+dmb.sy+ctrlisb",
                            {{STR(x, 1), dmb_sy(), STR(y, 1)}, {LDR(y, 0), with_ctrl(ISB(), 0), LDR(x, 1)}}, mp_final),
                       false));
  c.push_back(tutorial(
      make("LB+datas", {{LDR(x, 0), with_data(STR(y, 1), 0)}, {LDR(y, 1), with_data(STR(x, 1), 0)}}, lb_final), false));
  c.push_back(tutorial(
      make("LB+addrs", {{LDR(x, 0), with_addr(STR(y, 1), 0)}, {LDR(y, 1), with_addr(STR(x, 1), 0)}}, lb_final), false));
  c.push_back(tutorial(
      make("LB+ctrls", {{LDR(x, 0), with_ctrl(STR(y, 1), 0)}, {LDR(y, 1), with_ctrl(STR(x, 1), 0)}}, lb_final), false));

  // --- AArch64, clauses no published test isolates ---------------------------------------------------------
  c.push_back(from_model_text(
      make("LB+addr-po+dmb.sy", {{LDR(x, 0), with_addr(LDR(z, 2), 0), STR(y, 1)}, {LDR(y, 1), dmb_sy(), STR(x, 1)}},
           lb_final),
      false, "dob clause addr;po;[W]"));
  c.push_back(from_model_text(
      make("LB+dmb.sy+data-wsi", {{LDR(z, 0), dmb_sy(), STR(y, 1)}, {LDR(y, 1), with_data(STR(z, 1), 0), STR(z, 2)}},
           {{{0, 2}, {1, 1}}, {}}),
      false, "dob clause (ctrl|data);coi"));
  c.push_back(from_model_text(
      make("SB+amo.swpals",
           {{STR(x, 1), SWP(z, 1, 2, true, true), LDR(y, 0)}, {STR(y, 1), SWP(w, 1, 3, true, true), LDR(x, 1)}},
           sb_final),
      false, "bob clause po;[A];amo;[L];po"));
  c.push_back(from_model_text(
      make("MP+dmb.st+addr", {{STR(x, 1), DMB(ArmFence::store), STR(y, 1)}, {LDR(y, 0), with_addr(LDR(x, 1), 0)}},
           mp_final),
      false, "bob clause [W];po;[DMB.ST];po;[W]"));
  c.push_back(from_model_text(
      make("MP+rel-wsi+acq", {{STR(x, 1), STLR(y, 1), STR(y, 2)}, {LDAR(y, 0), LDR(x, 1)}}, {{{0, 2}, {1, 0}}, {}}),
      false, "bob clause po;[L];coi"));

  // --- C++ -------------------------------------------------------------------------------------------------
  constexpr Order rlx = Order::relaxed, acq = Order::acquire, rel = Order::release, sc = Order::seq_cst;
  const std::string rc11_paper = "Lahav et al., PLDI 2017 (RC11), §1-3";
  c.push_back(
      cpp(make("C++ SB rlx", {{store(x, 1, rlx), load(y, 0, rlx)}, {store(y, 1, rlx), load(x, 1, rlx)}}, sb_final),
          rc11_paper, kAllowed, kAllowed, kAllowed));
  c.push_back(
      cpp(make("C++ SB rel-acq", {{store(x, 1, rel), load(y, 0, acq)}, {store(y, 1, rel), load(x, 1, acq)}}, sb_final),
          rc11_paper + "; ARMv8: STLR;LDAR (SB+rel-acq is forbidden there)", kAllowed, kAllowed, kForbidden));
  c.push_back(cpp(make("C++ SB sc", {{store(x, 1, sc), load(y, 0, sc)}, {store(y, 1, sc), load(x, 1, sc)}}, sb_final),
                  rc11_paper, kForbidden, kForbidden, kForbidden));
  c.push_back(cpp(
      make("C++ SB rlx+sc-fences",
           {{store(x, 1, rlx), fence(sc), load(y, 0, rlx)}, {store(y, 1, rlx), fence(sc), load(x, 1, rlx)}}, sb_final),
      rc11_paper, kForbidden, kForbidden, kForbidden));
  c.push_back(cpp(make("C++ SB rlx+sc-fence+po",
                       {{store(x, 1, rlx), fence(sc), load(y, 0, rlx)}, {store(y, 1, rlx), load(x, 1, rlx)}}, sb_final),
                  rc11_paper + "; herd SB+dmb.sy+po", kAllowed, kAllowed, kAllowed));
  c.push_back(
      cpp(make("C++ MP rlx", {{store(x, 1, rlx), store(y, 1, rlx)}, {load(y, 0, rlx), load(x, 1, rlx)}}, mp_final),
          rc11_paper, kAllowed, kAllowed, kAllowed));
  c.push_back(
      cpp(make("C++ MP rel-acq", {{store(x, 1, rlx), store(y, 1, rel)}, {load(y, 0, acq), load(x, 1, rlx)}}, mp_final),
          rc11_paper, kForbidden, kForbidden, kForbidden));
  c.push_back(
      cpp(make("C++ MP rlx+rel-fence+acq-fence",
               {{store(x, 1, rlx), fence(rel), store(y, 1, rlx)}, {load(y, 0, rlx), fence(acq), load(x, 1, rlx)}},
               mp_final),
          rc11_paper + " (fence synchronisation)", kForbidden, kForbidden, kForbidden));
  c.push_back(
      cpp(make("C++ LB rlx", {{load(x, 0, rlx), store(y, 1, rlx)}, {load(y, 1, rlx), store(x, 1, rlx)}}, lb_final),
          rc11_paper + ": forbidden only by no-thin-air; ARMv8 allows LB", kForbidden, kAllowed, kAllowed));
  c.push_back(cpp(
      make("C++ LB acq-loads", {{load(x, 0, acq), store(y, 1, rlx)}, {load(y, 1, acq), store(x, 1, rlx)}}, lb_final),
      rc11_paper + "; ARMv8: LDAR orders later accesses", kForbidden, kAllowed, kForbidden));
  c.push_back(
      cpp(make("C++ CoRR rlx", {{store(x, 1, rlx)}, {load(x, 0, rlx), load(x, 1, rlx)}}, {{{0, 1}, {1, 0}}, {}}),
          rc11_paper + " (coherence)", kForbidden, kForbidden, kForbidden));
  c.push_back(cpp(
      make("C++ fetch_add atomicity", {{fetch_add(x, 1, 0, rlx)}, {fetch_add(x, 1, 1, rlx)}}, {{{0, 0}, {1, 0}}, {}}),
      rc11_paper + " (atomicity)", kForbidden, kForbidden, kForbidden));
  {
    const auto cas = [](int expected, int desired, Order o) {
      Instruction i = fetch_add(x, 0, -1, o);
      i.op = Op::cas;
      i.expected = expected;
      i.value = desired;
      return i;
    };
    // Both compare-exchanges 0 → 1 succeed (each program path is a success path): atomicity forbids it.
    c.push_back(cpp(make("C++ cas atomicity", {{cas(0, 1, rlx)}, {cas(0, 1, rlx)}}, {{}, {}}),
                    rc11_paper + " (atomicity)", kForbidden, kForbidden, kForbidden));
  }
  c.push_back(
      cpp(make("C++ 2+2W rlx", {{store(x, 2, rlx), store(y, 1, rlx)}, {store(y, 2, rlx), store(x, 1, rlx)}}, ww_final),
          rc11_paper, kAllowed, kAllowed, kAllowed));
  c.push_back(
      cpp(make("C++ 2+2W rel", {{store(x, 2, rlx), store(y, 1, rel)}, {store(y, 2, rlx), store(x, 1, rel)}}, ww_final),
          rc11_paper + "; ARMv8: STR;STLR is ordered (po;[L])", kAllowed, kAllowed, kForbidden));
  const FinalState iriw_final{{{0, 1}, {1, 0}, {2, 1}, {3, 0}}, {}};
  c.push_back(cpp(make("C++ IRIW rel-acq",
                       {{store(x, 1, rel)},
                        {store(y, 1, rel)},
                        {load(x, 0, acq), load(y, 1, acq)},
                        {load(y, 2, acq), load(x, 3, acq)}},
                       iriw_final),
                  rc11_paper + ": C++ is not multicopy-atomic; ARMv8 is, and LDAR orders", kAllowed, kAllowed,
                  kForbidden));
  c.push_back(cpp(
      make("C++ IRIW sc",
           {{store(x, 1, sc)}, {store(y, 1, sc)}, {load(x, 0, sc), load(y, 1, sc)}, {load(y, 2, sc), load(x, 3, sc)}},
           iriw_final),
      rc11_paper, kForbidden, kForbidden, kForbidden));
  c.push_back(cpp(make("C++ WRC rel-acq",
                       {{store(x, 1, rlx)}, {load(x, 0, rlx), store(y, 1, rel)}, {load(y, 1, acq), load(x, 2, rlx)}},
                       {{{0, 1}, {1, 1}, {2, 0}}, {}}),
                  rc11_paper + " (coherence through happens-before)", kForbidden, kForbidden, kForbidden));
  // The fetch_add whose result is unused, read-from a release store, then an acquire fence (LLVM issue
  // #69503): C++ forbids r0=0, since the fence synchronises with the release store through the RMW. With the
  // result unused LLVM emits STADD, whose read DMB ISHLD does not order (herd MP+rel+LDADDnoret-dmb.ld): the
  // ARMv8 program allows what C++ forbids. The mapping is unsound for this pattern; "C++ … (LDADD)" keeps the
  // result and is sound.
  LitmusTest faa = make("C++ MP rel + unused fetch_add + acq-fence (STADD)",
                        {{store(x, 1, rlx), store(y, 1, rel)}, {fetch_add(y, 1, -1, rlx), fence(acq), load(x, 0, rlx)}},
                        {{{0, 0}}, {{y, 2}}});
  c.push_back(cpp(faa, "LLVM issue #69503; herd MP+rel+LDADDnoret-dmb.ld", kForbidden, kForbidden, kAllowed));
  faa.name = "C++ MP rel + used fetch_add + acq-fence (LDADD)";
  faa.threads[1][0].reg = 1;
  faa.registers.push_back("r1");
  c.push_back(cpp(faa, "herd MP+rel+LDADD-dmb.ld", kForbidden, kForbidden, kForbidden));
  return c;
}

std::vector<std::string> untranscribed_aarch64_tests() {
  // A CAS whose expected value comes from a register loaded earlier, or that may fail (a read and no write), or
  // whose Rs register carries a dependency on its success path: the program model has only the success path of a
  // CAS against a constant.
  return {"CAS+data1", "CAS+data2", "LB+rel+CAS", "LB+rel+CAS+BIS", "LB+rel+CAS-ok-RsRs-addr", "LB+rel+CAS-ok-MRs-addr",
          "MP+rel+CAS-addr", "MP+rel+CAS-ok-RsRs-addr", "MP+rel+CAS-ok-MRs-addr", "MP+rel+CAS-ok-bothRs-addr",
          // A link to the pick catalogue (aarch64-pick), whose dependency rules are a later model's.
          "MP+rel+CSEL-addr"};
}

}  // namespace frontsteal::axiomatic
