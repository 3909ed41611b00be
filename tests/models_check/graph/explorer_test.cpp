// explorer_test.cpp — the execution-graph explorer (models_check/graph/explorer.hpp) against the axiomatic checker:
// every C++ program of the litmus catalogue and every protocol litmus program, run as code, has exactly the checker's
// consistent executions (po ∪ rf acyclic, no dependencies) under RC11 and both ARMv8 mappings, and reaches its final
// state exactly when the checker allows it; so do random programs of two and three threads. Random programs of two
// to five threads are explored without repetition. Each planted explorer defect breaks that agreement or (the
// maximality condition dropped) that optimality somewhere (the validation's negative controls). Fixed seeds.
#include <catch2/catch.hpp>

#include <random>
#include <string>

#include "models_check/axiomatic/litmus_catalogue.hpp"
#include "models_check/axiomatic/protocol_litmus.hpp"
#include "models_check/graph/litmus_agreement.hpp"
#include "models_check/graph/stealing_program.hpp"

namespace ax = frontsteal::axiomatic;
namespace graph = frontsteal::graph;

namespace {

constexpr graph::GraphModel kModels[] = {graph::GraphModel::rc11, graph::GraphModel::armv8_ldar,
                                         graph::GraphModel::armv8_ldapr};

// `threads` threads of one to `length` C++ accesses over x and y: loads, stores, fetch_adds, exchanges and fences,
// in every order that fits the access.
ax::LitmusTest random_program(std::mt19937& rng, int threads, int length) {
  const auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  ax::LitmusTest t;
  t.name = "random";
  t.locations = {"x", "y"};
  int reg = 0;
  for (int th = 0; th < threads; ++th) {
    std::vector<ax::Instruction> code;
    const int n = 1 + pick(length);
    for (int k = 0; k < n; ++k) {
      ax::Instruction in;
      in.location = pick(2);
      in.order = static_cast<ax::Order>(pick(5));
      const int kind = pick(10);
      if (kind < 4) {
        in.op = ax::Op::load;
        in.reg = reg++;
        if (in.order == ax::Order::release || in.order == ax::Order::acq_rel) in.order = ax::Order::acquire;
      } else if (kind < 7) {
        in.op = ax::Op::store;
        in.value = 1 + pick(2);
        if (in.order == ax::Order::acquire || in.order == ax::Order::acq_rel) in.order = ax::Order::release;
      } else if (kind < 8) {
        in.op = ax::Op::fetch_add;
        in.value = 1;
        in.reg = reg++;
      } else if (kind < 9) {
        in.op = ax::Op::exchange;
        in.value = 3;
        in.reg = reg++;
      } else {
        in.op = ax::Op::fence;
        in.location = -1;
        if (in.order == ax::Order::relaxed) in.order = ax::Order::seq_cst;
      }
      code.push_back(in);
    }
    t.threads.push_back(code);
  }
  t.registers.assign(static_cast<std::size_t>(reg), "r");
  t.final_state.registers.push_back({0, 1});
  return t;
}

std::vector<ax::LitmusTest> cpp_programs() {
  std::vector<ax::LitmusTest> out;
  for (const ax::CatalogueEntry& e : ax::litmus_catalogue()) {
    if (e.is_cpp) out.push_back(e.test);
  }
  for (const auto& family :
       {ax::handshake_litmus_all(), ax::reread_litmus_all(), ax::termination_litmus_all(), ax::lock_litmus_all()}) {
    for (const ax::ProtocolLitmus& p : family) out.push_back(p.test);
  }
  return out;
}

// The first disagreement over `programs` under every model, or empty.
std::string first_disagreement(const std::vector<ax::LitmusTest>& programs, graph::ExplorerDefect defect) {
  for (const ax::LitmusTest& t : programs) {
    for (graph::GraphModel m : kModels) {
      const graph::LitmusAgreement a = graph::compare_with_checker(t, m, defect);
      if (!a.agrees()) {
        return t.name + " under " + std::string(graph::name(m)) + ": checker " + std::to_string(a.checker_executions) +
               (a.checker_allowed ? " allowed" : " forbidden") + ", explorer " + std::to_string(a.distinct) +
               (a.explorer_allowed ? " allowed" : " forbidden");
      }
    }
  }
  return {};
}

std::vector<ax::LitmusTest> random_programs(int count, int threads, int length, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<ax::LitmusTest> out;
  for (int k = 0; k < count; ++k) out.push_back(random_program(rng, threads, length));
  return out;
}

}  // namespace

TEST_CASE("the catalogue's C++ programs and the protocol's litmus programs, run as code, agree with the checker",
          "[graph]") {
  const auto programs = cpp_programs();
  REQUIRE(programs.size() > 30);
  INFO(first_disagreement(programs, graph::ExplorerDefect::none));
  CHECK(first_disagreement(programs, graph::ExplorerDefect::none).empty());
}

TEST_CASE("random programs of two and three threads agree with the checker", "[graph]") {
  std::vector<ax::LitmusTest> programs = random_programs(150, 2, 4, 11);
  for (const auto& t : random_programs(100, 3, 2, 12)) programs.push_back(t);
  const std::string found = first_disagreement(programs, graph::ExplorerDefect::none);
  INFO(found);
  CHECK(found.empty());
}

namespace {

// Runs that reach an execution already explored, over `programs` under every model.
std::uint64_t repeated_runs(const std::vector<ax::LitmusTest>& programs, graph::ExplorerDefect defect) {
  std::uint64_t repeated = 0;
  for (const auto& t : programs) {
    for (graph::GraphModel m : kModels) {
      graph::LitmusProgram program(t);
      graph::ExploreOptions o;
      o.model = m;
      o.stop_at_failure = false;
      o.defect = defect;
      const graph::ExploreResult r = graph::explore(program, o);
      repeated += r.complete - r.distinct;
    }
  }
  return repeated;
}

std::vector<ax::LitmusTest> programs_of_two_to_five_threads() {
  std::vector<ax::LitmusTest> programs = random_programs(100, 2, 4, 11);
  for (const auto& t : random_programs(100, 3, 3, 21)) programs.push_back(t);
  for (const auto& t : random_programs(50, 4, 2, 22)) programs.push_back(t);
  for (const auto& t : random_programs(20, 5, 2, 23)) programs.push_back(t);
  return programs;
}

}  // namespace

TEST_CASE("programs of two to five threads are explored without repetition", "[graph]") {
  CHECK(repeated_runs(programs_of_two_to_five_threads(), graph::ExplorerDefect::none) == 0);
}

// The maximality condition's negative control: without it the same programs repeat executions.
TEST_CASE("without the maximality condition executions repeat", "[graph]") {
  CHECK(repeated_runs(programs_of_two_to_five_threads(), graph::ExplorerDefect::no_maximality) > 0);
}

TEST_CASE("each planted explorer defect breaks the agreement", "[graph]") {
  std::vector<ax::LitmusTest> programs = cpp_programs();
  for (const auto& t : random_programs(100, 2, 3, 13)) programs.push_back(t);
  for (const auto defect : {graph::ExplorerDefect::no_revisits, graph::ExplorerDefect::co_last_only,
                            graph::ExplorerDefect::no_final_check}) {
    INFO("defect " << static_cast<int>(defect));
    CHECK_FALSE(first_disagreement(programs, defect).empty());
  }
}

// Paper duplicates an item under RC11 and with LDAPR but not with LDAR, and the counterexample names core/'s sites
// and lines.
TEST_CASE("core/'s own handshake under Paper: duplicate under RC11 and LDAPR and none under LDAR", "[graph]") {
  namespace model = frontsteal::model;
  const model::ScenarioSpec& handshake = model::scenarios().front();
  REQUIRE(handshake.name == "owner_vs_thief");
  for (const auto& p : model::known_stealing_policies()) {
    if (p.name == "Paper") model::current_table() = p;
  }
  const auto run = [&](graph::GraphModel m) {
    graph::StealingProgram program(handshake, model::CheckMode::kExactlyOnce);
    graph::ExploreOptions o;
    o.model = m;
    o.bound = 1;
    return graph::explore(program, o);
  };
  const graph::ExploreResult rc11 = run(graph::GraphModel::rc11);
  CHECK(rc11.outcome.verdict == model::Verdict::kDuplicate);
  CHECK(rc11.witness.find("[T5 thief.reread_front]") != std::string::npos);
  CHECK(rc11.witness.find("core/stealing_protocol.hpp:") != std::string::npos);
  CHECK(run(graph::GraphModel::armv8_ldapr).outcome.verdict == model::Verdict::kDuplicate);
  const graph::ExploreResult ldar = run(graph::GraphModel::armv8_ldar);
  CHECK(ldar.outcome.verdict == model::Verdict::kPass);
  CHECK_FALSE(ldar.bounded);
  CHECK(ldar.complete > 0);
  CHECK(ldar.complete == ldar.distinct);
}
