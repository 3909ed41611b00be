// program.hpp — a litmus program: a few threads of straight-line atomic accesses and fences, and the final
// state whose reachability is asked.
//
// An instruction carries two views. The C++ view (`order`) is what RC11 reads. The ARMv8 view (`arm`) is what
// the ARMv8 model reads: written directly for the AArch64 catalogue's tests, or produced from the C++ view by
// compile_to_armv8() with the standard mapping (Sewell et al.'s C/C++11 mappings page; ARM's own ABI notes):
//   load   relaxed → LDR        acquire, seq_cst → LDAR (A)
//   store  relaxed → STR        release, seq_cst → STLR (L)
//   fence  acquire → DMB ISHLD  release, acq_rel, seq_cst → DMB ISH
//   fetch_add (ARMv8.1 LSE) relaxed → LDADD, acquire → LDADDA (A), release → LDADDL (L), acq_rel, seq_cst →
//   LDADDAL (A and L); when the result is unused and the order has no acquire, the compiler may emit STADD /
//   STADDL instead, whose read is not a read for DMB ISHLD's ordering (the case of LLVM issues #69503, #68428).
// Values are small integers; a location starts at its `initial` value (0 unless given). A fetch_add writes the value it
// read plus its operand, an exchange its operand.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace frontsteal::axiomatic {

enum class Order : std::uint8_t { relaxed, acquire, release, acq_rel, seq_cst };
// exchange: SWP / atomic exchange. cas: a compare-exchange on its success path (it reads `expected` and writes
// `value`; a candidate in which it reads anything else is not an execution of this program).
enum class Op : std::uint8_t { load, store, fetch_add, exchange, cas, fence };
// DMB ISH (SY), DMB ISHLD, DMB ISHST, and ISB (an instruction barrier: it orders only through dob's
// (ctrl | addr;po);[ISB];po;[R] clause).
enum class ArmFence : std::uint8_t { none, full, load, store, isb };

struct ArmAccess {
  bool acquire = false;     // LDAR / LDADDA / LDADDAL: the read is an A
  bool acquire_pc = false;  // LDAPR: the read is a Q (acquirePC: ordered before later accesses, not after L)
  bool release = false;     // STLR / LDADDL / LDADDAL / STADDL: the write is an L
  ArmFence fence = ArmFence::none;
  bool result_unused = false;  // STADD(L): the read is not ordered by DMB ISHLD
};

struct Instruction {
  Op op = Op::load;
  int location = -1;  // index into LitmusTest::locations; −1 for fences
  int value = 0;      // the value a store, an exchange or a cas writes, or a fetch_add's operand
  int expected = 0;   // cas: the value it must read
  int reg = -1;       // load / fetch_add: the register that receives the value read (−1: unused)
  Order order = Order::relaxed;
  ArmAccess arm;
  // ARMv8 only: the value written depends on what the instruction at this index of the same thread read (a data
  // dependency, dob). The value itself stays `value`: the catalogue's tests make the dependency a no-op (w|1).
  int data_from = -1;
  // ARMv8 only: the address this instruction accesses is computed from what the instruction at this index read (an
  // address dependency: both its read and its write depend). The location stays `location`: the catalogue's tests
  // add a value that is always 0 (EOR w,w,w).
  int addr_from = -1;
  // ARMv8 only: this instruction and every later one of the thread run after a branch on what the instruction at
  // this index read (a control dependency; dob orders that read before each of those writes).
  int ctrl_from = -1;
  std::string label;  // a protocol site label (core/site.hpp) where the program models the protocol
};

struct RegisterIs {
  int reg;
  int value;
};
struct MemoryIs {
  int location;
  int value;
};

// The final state asked about: every listed register and location has its value.
struct FinalState {
  std::vector<RegisterIs> registers;
  std::vector<MemoryIs> memory;
};

struct LitmusTest {
  std::string name;
  std::vector<std::string> locations;
  std::vector<std::string> registers;  // names, for printing ("1:r0")
  std::vector<std::vector<Instruction>> threads;
  FinalState final_state;
  std::vector<int> initial;  // initial value per location; missing ones are 0
};

// The standard C++ → ARMv8 mapping (above) of one instruction's C++ order. `use_stadd`: a fetch_add whose result is
// unused and whose order has no acquire becomes ST<OP> (what LLVM emits for it). `acquire_pc`: an acquire (not
// seq_cst) load becomes LDAPR, the RCpc mapping compilers use from ARMv8.3.
inline ArmAccess armv8_view(const Instruction& in, bool use_stadd = true, bool acquire_pc = false) {
  const bool acq = in.order == Order::acquire || in.order == Order::acq_rel || in.order == Order::seq_cst;
  const bool rel = in.order == Order::release || in.order == Order::acq_rel || in.order == Order::seq_cst;
  ArmAccess arm;
  switch (in.op) {
    case Op::load:
      arm.acquire = acq && !(acquire_pc && in.order == Order::acquire);
      arm.acquire_pc = acquire_pc && in.order == Order::acquire;
      break;
    case Op::store: arm.release = rel; break;
    case Op::fetch_add:
    case Op::exchange:
    case Op::cas:
      arm.acquire = acq;
      arm.release = rel;
      arm.result_unused = use_stadd && in.reg < 0 && !acq && in.op != Op::cas;  // CAS has no ST form
      break;
    case Op::fence: arm.fence = in.order == Order::acquire ? ArmFence::load : ArmFence::full; break;
  }
  return arm;
}

// The mapping applied to every instruction of a program.
inline LitmusTest compile_to_armv8(LitmusTest test, bool use_stadd = true, bool acquire_pc = false) {
  for (auto& thread : test.threads) {
    for (Instruction& in : thread) in.arm = armv8_view(in, use_stadd, acquire_pc);
  }
  return test;
}

}  // namespace frontsteal::axiomatic
