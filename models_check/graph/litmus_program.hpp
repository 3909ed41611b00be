// litmus_program.hpp — a litmus program (models_check/axiomatic/program.hpp) run as code through the explorer: each
// thread executes its instructions as backend calls, so the explorer's executions of it can be compared with the
// axiomatic checker's enumeration of the same program (validation.cpp's job).
//
// A compare-exchange on its success path only, as the catalogue means it: a run in which it would fail is dropped
// (runtime::assume), as the axiomatic checker skips such candidates as "another program path".
#pragma once

#include <map>
#include <vector>

#include "models_check/axiomatic/execution.hpp"
#include "models_check/graph/explorer.hpp"

namespace frontsteal::graph {

class LitmusProgram final : public Program {
 public:
  explicit LitmusProgram(const ax::LitmusTest& test) : test_(test) {}

  int threads() const override { return static_cast<int>(test_.threads.size()); }

  void setup() override {
    locations_.clear();
    for (std::size_t l = 0; l < test_.locations.size(); ++l) {
      const int initial = l < test_.initial.size() ? test_.initial[l] : 0;
      locations_.push_back(runtime::new_location(encode(initial), false));
    }
    registers_.assign(test_.registers.size() + 8, 0);
  }

  void run_thread(int t) override {
    for (const ax::Instruction& in : test_.threads[static_cast<std::size_t>(t)]) {
      Access a;
      a.order = to_mo(in.order);
      a.file = test_.name.c_str();
      const int loc = in.location >= 0 ? locations_[static_cast<std::size_t>(in.location)] : -1;
      switch (in.op) {
        case ax::Op::load: keep(in, decode<int>(runtime::load(loc, a))); break;
        case ax::Op::store: runtime::store(loc, encode(in.value), a); break;
        case ax::Op::fetch_add:
          keep(in, decode<int>(runtime::read_modify_write(
                       loc, ax::Op::fetch_add,
                       [&](Value old) { return std::optional<Value>(encode(decode<int>(old) + in.value)); }, a)));
          break;
        case ax::Op::exchange:
          keep(in, decode<int>(runtime::read_modify_write(
                       loc, ax::Op::exchange, [&](Value) { return std::optional<Value>(encode(in.value)); }, a)));
          break;
        case ax::Op::cas: {
          bool won = false;
          const int seen = decode<int>(runtime::read_modify_write(
              loc, ax::Op::cas,
              [&](Value old) -> std::optional<Value> {
                won = decode<int>(old) == in.expected;
                return won ? std::optional<Value>(encode(in.value)) : std::nullopt;
              },
              a));
          runtime::assume(won);
          keep(in, seen);
          break;
        }
        case ax::Op::fence: runtime::fence(in.order, a); break;
      }
    }
  }

  Outcome check(const Graph& g) override {
    bool reached = true;
    for (const ax::RegisterIs& r : test_.final_state.registers) reached = reached && registers_[r.reg] == r.value;
    for (const ax::MemoryIs& m : test_.final_state.memory) {
      const auto& co = g.locations[static_cast<std::size_t>(locations_[m.location])].co;
      reached = reached && decode<int>(g.events[co.back()].value) == m.value;
    }
    if (reached) return {Verdict::kOtherFailure, "final state reached"};
    return {};
  }

  void teardown() override {}

 private:
  static Mo to_mo(ax::Order o) {
    switch (o) {
      case ax::Order::relaxed: return Mo::kRelaxed;
      case ax::Order::acquire: return Mo::kAcquire;
      case ax::Order::release: return Mo::kRelease;
      case ax::Order::acq_rel: return Mo::kAcqRel;
      case ax::Order::seq_cst: return Mo::kSeqCst;
    }
    return Mo::kSeqCst;
  }
  void keep(const ax::Instruction& in, int value) {
    if (in.reg >= 0) registers_[static_cast<std::size_t>(in.reg)] = value;
  }

  const ax::LitmusTest& test_;
  std::vector<int> locations_;
  std::vector<int> registers_;
};

}  // namespace frontsteal::graph
