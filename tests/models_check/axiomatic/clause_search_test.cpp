// clause_search_test.cpp — aob's rmw clause of the ARMv8 model (models_check/axiomatic/models.hpp) is implied by
// the others: dropping it changes the consistency of no candidate execution of the catalogue's AArch64 programs,
// of the C++ ones and the protocol's programs after the mapping, or of random two-thread AArch64 programs (the
// claim behind implied_by_other_clauses()). The same comparison does tell a clause that matters (the planted
// check: ctrl;[W], DMB.FULL or the internal axiom's fr dropped). Fixed seeds, so every run explores the same programs.
#include <catch2/catch.hpp>

#include <random>
#include <string>

#include "models_check/axiomatic/checker.hpp"
#include "models_check/axiomatic/litmus_catalogue.hpp"
#include "models_check/axiomatic/protocol_litmus.hpp"

namespace ax = frontsteal::axiomatic;

namespace {

// Two threads of one to three instructions over x, y, z: loads (plain, LDAR, LDAPR), stores (plain,
// STLR), SWP / LDADD / CAS with any of acquire, release and a discarded result, every barrier and ISB, and
// address, data and control dependencies on earlier instructions of the thread.
ax::LitmusTest random_program(std::mt19937& rng) {
  const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  ax::LitmusTest t;
  t.name = "random";
  t.locations = {"x", "y", "z"};
  const int threads = 2;
  for (int th = 0; th < threads; ++th) {
    std::vector<ax::Instruction> thread;
    const int length = 1 + pick(3);
    for (int i = 0; i < length; ++i) {
      ax::Instruction in;
      in.location = pick(3);
      in.value = 1 + pick(2);
      switch (pick(7)) {
        case 0:
        case 1: in.op = ax::Op::load; break;
        case 2: in.op = ax::Op::store; break;
        case 3: in.op = ax::Op::exchange; break;
        case 4:
          in.op = ax::Op::fetch_add;
          in.value = 1;
          break;
        case 5:
          in.op = ax::Op::cas;
          in.expected = pick(2);
          break;
        default:
          in.op = ax::Op::fence;
          in.location = -1;
          in.arm.fence = static_cast<ax::ArmFence>(1 + pick(4));
      }
      if (in.op != ax::Op::fence) {
        in.arm.acquire = in.op != ax::Op::store && pick(3) == 0;
        in.arm.release = in.op != ax::Op::load && pick(3) == 0;
        if (in.op != ax::Op::store && in.op != ax::Op::load && pick(4) == 0) {
          in.arm.result_unused = true;
          in.arm.acquire = false;
        }
        if (in.op == ax::Op::load && !in.arm.acquire && pick(4) == 0) in.arm.acquire_pc = true;
      }
      if (i > 0 && pick(3) == 0) in.data_from = pick(i);
      if (i > 0 && pick(4) == 0) in.addr_from = pick(i);
      if (i > 0 && pick(4) == 0) in.ctrl_from = pick(i);
      thread.push_back(in);
    }
    t.threads.push_back(thread);
  }
  return t;
}

// The first execution, among every candidate of `programs`, that is ARMv8-consistent with the clause and not
// without it, or the other way round; its description, or empty when there is none.
std::string execution_the_clause_decides(ax::ModelDefect clause, const std::vector<ax::LitmusTest>& programs) {
  for (const ax::LitmusTest& t : programs) {
    std::string found;
    ax::for_each_candidate(t, [&](const ax::Execution& x) {
      if (ax::armv8_consistent(x) == ax::armv8_consistent(x, clause)) return true;
      found = t.name + ":\n" + ax::describe(x);
      return false;
    });
    if (!found.empty()) return found;
  }
  return {};
}

// The catalogue's programs as ARMv8 sees them, the protocol's under both acquire mappings, and `random` random
// two-thread AArch64 programs.
std::vector<ax::LitmusTest> programs_to_search(int random) {
  std::vector<ax::LitmusTest> programs;
  for (const ax::CatalogueEntry& e : ax::litmus_catalogue()) {
    programs.push_back(e.is_cpp ? ax::compile_to_armv8(e.test) : e.test);
  }
  for (const auto& family : {ax::handshake_litmus_all(), ax::reread_litmus_all(), ax::termination_litmus_all(),
                             ax::publication_litmus_all(), ax::lock_litmus_all(), ax::chase_lev_litmus_all()}) {
    for (const ax::ProtocolLitmus& p : family) {
      programs.push_back(ax::compile_to_armv8(p.test));
      programs.push_back(ax::compile_to_armv8(p.test, true, true));
    }
  }
  std::mt19937 rng(7);
  for (int k = 0; k < random; ++k) programs.push_back(random_program(rng));
  return programs;
}

}  // namespace

TEST_CASE("aob's rmw clause is implied: dropping it changes no execution's consistency", "[axiomatic][armv8]") {
  CHECK_FALSE(ax::implied_by_other_clauses(ax::ModelDefect::armv8_aob_without_rmw).empty());
  const std::string found =
      execution_the_clause_decides(ax::ModelDefect::armv8_aob_without_rmw, programs_to_search(20000));
  INFO(found);
  CHECK(found.empty());
}

TEST_CASE("the same comparison tells clauses that matter", "[axiomatic][armv8]") {
  const std::vector<ax::LitmusTest> programs = programs_to_search(3000);
  for (const ax::ModelDefect clause :
       {ax::ModelDefect::armv8_dob_without_ctrl_write, ax::ModelDefect::armv8_internal_without_fr,
        ax::ModelDefect::armv8_bob_without_dmb_full}) {
    CHECK(ax::implied_by_other_clauses(clause).empty());
    CHECK_FALSE(execution_the_clause_decides(clause, programs).empty());
  }
}
