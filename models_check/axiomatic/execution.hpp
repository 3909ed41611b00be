// execution.hpp — the candidate executions of a litmus program: events, and every choice of reads-from and
// coherence order.
//
// Events: one initial write per location (the initial state, its own "thread" −1), then each thread's
// instructions in program order: a load is a read, a store a write, a fence a fence, a fetch_add or exchange a
// read and a write joined by `rmw`. A candidate execution picks, for every read, the write it reads from (any write to
// the location: rf), and for every location a total order of its writes with the initial write first (co). Values
// follow: a read has its write's value, a fetch_add's write the value its read got plus the operand; a choice
// where that definition goes round in a circle (a fetch_add reading, through others, from itself) gives no
// values and is skipped — every model forbids it (it is an rf;rmw cycle through co). The models (models.hpp)
// decide which candidates are consistent; the checker (checker.hpp) asks whether a consistent one reaches the
// final state.
#pragma once

#include <algorithm>
#include <functional>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "models_check/axiomatic/program.hpp"
#include "models_check/axiomatic/relation.hpp"

namespace frontsteal::axiomatic {

enum class EventKind : std::uint8_t { read, write, fence };

struct Event {
  EventKind kind;
  int thread;                                // −1: the initial writes
  int index;                                 // position in the thread's instruction list (−1 for initial writes)
  int location;                              // −1 for fences
  const Instruction* instruction = nullptr;  // null for initial writes
  bool is_rmw_part = false;
};

// One execution over a set type (relation.hpp): EventSet for litmus programs, WideSet for the execution graphs of
// whole protocol runs (models_check/graph/). The models (models.hpp) read only these members.
template <class Set>
struct BasicExecution {
  using Rel = BasicRelation<Set>;
  const LitmusTest* test = nullptr;  // the litmus program, when there is one (printing only)
  std::vector<Event> events;
  int event_count = 0;
  // Fixed by the program:
  Rel po;   // program order (transitive; the initial writes are not in it)
  Rel rmw;  // a fetch_add's read → its write
  Rel same_location;
  Set reads{}, writes{}, fences{}, initial{};
  // ARMv8's dependencies, read → dependent event: data (the read of instruction data_from → the write that uses
  // its value), addr (the read of instruction addr_from → the accesses whose address it computes) and ctrl (the
  // read a branch tested → every event at or after the instruction that names it).
  Rel addr, data, ctrl;
  // Chosen per candidate:
  Rel rf, co;
  std::vector<int> value;  // per event: the value read or written (fences: 0)

  bool same_thread(int a, int b) const { return events[a].thread == events[b].thread && events[a].thread >= 0; }
  Rel internal() const {
    Rel r(event_count);
    for (int a = 0; a < event_count; ++a) {
      for (int b = 0; b < event_count; ++b) {
        if (same_thread(a, b)) r.add(a, b);
      }
    }
    return r;
  }
  Rel external() const { return Rel::product(event_count, all(), all()).minus(internal()); }
  Rel fr() const {  // from-reads: a read → every write co-after the one it read from
    return rf.inverse().then(co).minus(Rel::identity(event_count, all()));
  }
  Set all() const { return first<Set>(event_count); }
};
using Execution = BasicExecution<EventSet>;

// The program's events and fixed relations (rf, co and values are filled per candidate).
inline Execution events_of(const LitmusTest& test) {
  Execution x;
  x.test = &test;
  for (int loc = 0; loc < static_cast<int>(test.locations.size()); ++loc) {
    x.events.push_back({EventKind::write, -1, -1, loc, nullptr});
  }
  for (int t = 0; t < static_cast<int>(test.threads.size()); ++t) {
    for (int i = 0; i < static_cast<int>(test.threads[t].size()); ++i) {
      const Instruction& in = test.threads[t][i];
      switch (in.op) {
        case Op::load: x.events.push_back({EventKind::read, t, i, in.location, &in}); break;
        case Op::store: x.events.push_back({EventKind::write, t, i, in.location, &in}); break;
        case Op::fence: x.events.push_back({EventKind::fence, t, i, -1, &in}); break;
        case Op::fetch_add:
        case Op::exchange:
        case Op::cas:
          x.events.push_back({EventKind::read, t, i, in.location, &in, true});
          x.events.push_back({EventKind::write, t, i, in.location, &in, true});
          break;
      }
    }
  }
  if (x.events.size() > static_cast<std::size_t>(kMaxEvents)) {
    throw std::invalid_argument(test.name + ": more than 64 events");
  }
  x.event_count = static_cast<int>(x.events.size());
  const int n = x.event_count;
  x.po = Relation(n), x.rmw = Relation(n), x.same_location = Relation(n), x.rf = Relation(n), x.co = Relation(n);
  for (int a = 0; a < n; ++a) {
    const Event& ea = x.events[a];
    if (ea.kind == EventKind::read) x.reads |= bit(a);
    if (ea.kind == EventKind::write) x.writes |= bit(a);
    if (ea.kind == EventKind::fence) x.fences |= bit(a);
    if (ea.thread < 0) x.initial |= bit(a);
    for (int b = 0; b < n; ++b) {
      const Event& eb = x.events[b];
      if (ea.location >= 0 && ea.location == eb.location) x.same_location.add(a, b);
      if (ea.thread >= 0 && ea.thread == eb.thread && a < b) x.po.add(a, b);
    }
    if (ea.is_rmw_part && ea.kind == EventKind::read) x.rmw.add(a, a + 1);
  }
  x.addr = Relation(n), x.data = Relation(n), x.ctrl = Relation(n);
  const auto read_of = [&](int thread, int index) {
    for (int r = 0; r < n; ++r) {
      if (x.events[r].kind == EventKind::read && x.events[r].thread == thread && x.events[r].index == index) return r;
    }
    return -1;
  };
  for (int e = 0; e < n; ++e) {
    const Event& ev = x.events[e];
    if (ev.instruction == nullptr) continue;
    if (ev.kind == EventKind::write && ev.instruction->data_from >= 0) {
      if (const int r = read_of(ev.thread, ev.instruction->data_from); r >= 0) x.data.add(r, e);
    }
    if (ev.kind != EventKind::fence && ev.instruction->addr_from >= 0) {
      if (const int r = read_of(ev.thread, ev.instruction->addr_from); r >= 0) x.addr.add(r, e);
    }
    for (int earlier = 0; earlier <= ev.index; ++earlier) {
      const int branch_on = test.threads[ev.thread][earlier].ctrl_from;
      if (branch_on < 0) continue;
      if (const int r = read_of(ev.thread, branch_on); r >= 0) x.ctrl.add(r, e);
    }
  }
  return x;
}

// Calls `visit(x)` for every candidate execution of the program; stops early when it returns false.
// Returns the number of candidates visited.
inline long for_each_candidate(const LitmusTest& test, const std::function<bool(const Execution&)>& visit) {
  Execution x = events_of(test);
  const int n = x.event_count;
  std::vector<int> reads;
  std::vector<std::vector<int>> writes_to(test.locations.size());
  for (int e = 0; e < n; ++e) {
    if (x.reads & bit(e)) reads.push_back(e);
    if ((x.writes & bit(e)) && !(x.initial & bit(e))) writes_to[x.events[e].location].push_back(e);
  }
  std::vector<int> source(reads.size());  // rf choice per read: index into the location's writes, −1: initial
  std::vector<std::vector<int>> co_order = writes_to;  // per location, a permutation (initial first)
  for (auto& w : co_order) std::sort(w.begin(), w.end());
  long visited = 0;
  bool go_on = true;

  const auto initial_value = [&](int loc) {
    return loc < static_cast<int>(test.initial.size()) ? test.initial[loc] : 0;
  };
  const auto resolve_values = [&]() {
    x.value.assign(n, 0);
    std::vector<int> state(n, 0);  // 0 unknown, 1 in progress, 2 done
    std::vector<int> read_source(n, -1);
    for (std::size_t r = 0; r < reads.size(); ++r) {
      const int loc = x.events[reads[r]].location;
      read_source[reads[r]] = source[r] < 0 ? loc : writes_to[loc][source[r]];  // initial write = event `loc`
    }
    std::function<bool(int)> value_of = [&](int e) -> bool {
      if (state[e] == 2) return true;
      if (state[e] == 1) return false;  // a value defined through itself
      state[e] = 1;
      const Event& ev = x.events[e];
      if (ev.kind == EventKind::read) {
        if (!value_of(read_source[e])) return false;
        x.value[e] = x.value[read_source[e]];
        // A cas on its success path reads what it expects; reading anything else is another path.
        if (ev.instruction != nullptr && ev.instruction->op == Op::cas && x.value[e] != ev.instruction->expected) {
          return false;
        }
      } else if (ev.kind == EventKind::write && ev.instruction == nullptr) {
        x.value[e] = initial_value(ev.location);
      } else if (ev.kind == EventKind::write) {
        if (ev.is_rmw_part && ev.instruction->op == Op::fetch_add) {
          if (!value_of(e - 1)) return false;
          x.value[e] = x.value[e - 1] + ev.instruction->value;
        } else {
          x.value[e] = ev.instruction->value;
        }
      }
      state[e] = 2;
      return true;
    };
    for (int e = 0; e < n; ++e) {
      if (!value_of(e)) return false;
    }
    return true;
  };

  const std::function<void(std::size_t)> choose_co = [&](std::size_t loc) {
    if (!go_on) return;
    if (loc == co_order.size()) {
      x.rf = Relation(n);
      for (std::size_t r = 0; r < reads.size(); ++r) {
        const int l = x.events[reads[r]].location;
        x.rf.add(source[r] < 0 ? l : writes_to[l][source[r]], reads[r]);
      }
      x.co = Relation(n);
      for (std::size_t l = 0; l < co_order.size(); ++l) {
        for (std::size_t i = 0; i < co_order[l].size(); ++i) {
          x.co.add(static_cast<int>(l), co_order[l][i]);  // the initial write is co-first
          for (std::size_t j = i + 1; j < co_order[l].size(); ++j) x.co.add(co_order[l][i], co_order[l][j]);
        }
      }
      if (!resolve_values()) return;
      ++visited;
      go_on = visit(x);
      return;
    }
    std::vector<int>& order = co_order[loc];
    std::sort(order.begin(), order.end());
    do {
      choose_co(loc + 1);
    } while (go_on && std::next_permutation(order.begin(), order.end()));
  };
  const std::function<void(std::size_t)> choose_rf = [&](std::size_t r) {
    if (!go_on) return;
    if (r == reads.size()) {
      choose_co(0);
      return;
    }
    const int loc = x.events[reads[r]].location;
    for (int s = -1; s < static_cast<int>(writes_to[loc].size()) && go_on; ++s) {
      source[r] = s;
      choose_rf(r + 1);
    }
  };
  choose_rf(0);
  return visited;
}

// The value the final state holds at `location`: the co-last write's.
inline int final_value(const Execution& x, int location) {
  int last = location;  // the initial write
  for (int e = 0; e < x.event_count; ++e) {
    if ((x.writes & bit(e)) && x.events[e].location == location && (x.co.successors(e) & x.writes) == 0) last = e;
  }
  return x.value[last];
}

// The value register `reg` holds at the end: the value read by the (last) instruction that writes it; 0 if none.
inline int register_value(const Execution& x, int reg) {
  int v = 0;
  for (int e = 0; e < x.event_count; ++e) {
    const Event& ev = x.events[e];
    if (ev.kind == EventKind::read && ev.instruction != nullptr && ev.instruction->reg == reg) v = x.value[e];
  }
  return v;
}

inline bool reaches(const Execution& x, const FinalState& f) {
  for (const RegisterIs& r : f.registers) {
    if (register_value(x, r.reg) != r.value) return false;
  }
  for (const MemoryIs& m : f.memory) {
    if (final_value(x, m.location) != m.value) return false;
  }
  return true;
}

}  // namespace frontsteal::axiomatic
