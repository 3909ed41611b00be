// execution_graph.hpp — the execution graph of one run of real code: its events, reads-from and coherence order,
// and the order in which the explorer added the events.
//
// An event is what one backend call did to shared memory: a read, a write, or a fence; a read-modify-write is a
// read and a write of the same instruction, adjacent in program order (RMW). Locations are the program's atomics
// and plain cells, numbered in the order the program created them; each starts with an initial write (thread −1)
// whose value is what the program stored into it before its threads started. Program order is each thread's
// event list; rf names, for each read, the write it reads; co is, per location, the order of its writes, initial
// write first. `stamp` is the order of addition (TruSt's ≤G): every read's write and every program-order
// predecessor carry a smaller stamp, which the explorer keeps true through its revisits (explorer.cpp).
//
// The memory models' axioms are not restated here: as_execution() turns the graph into the axiomatic checker's
// execution type (models_check/axiomatic/execution.hpp, on wide event sets) and models.hpp decides.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/site.hpp"
#include "models_check/axiomatic/execution.hpp"
#include "models_check/axiomatic/program.hpp"

namespace frontsteal::graph {

namespace ax = frontsteal::axiomatic;

// A value as the program stored it: up to 16 bytes of a trivially copyable type (a list entry is three ids).
struct Value {
  std::uint64_t lo = 0, hi = 0;
  friend bool operator==(const Value&, const Value&) = default;
};

template <class T>
Value encode(const T& v) {
  static_assert(std::is_trivially_copyable_v<T> && sizeof(T) <= sizeof(Value), "a shared value must fit 16 bytes");
  Value out;
  std::memcpy(static_cast<void*>(&out), static_cast<const void*>(&v), sizeof(T));
  return out;
}
template <class T>
T decode(const Value& v) {
  T out;
  std::memcpy(static_cast<void*>(&out), static_cast<const void*>(&v), sizeof(T));
  return out;
}

struct GraphEvent {
  ax::EventKind kind = ax::EventKind::read;
  int thread = -1;              // −1: an initial write
  int location = -1;            // −1: a fence
  Value value;                  // read: the value read; write: the value written
  ax::Instruction instruction;  // op and C++ order (the ARMv8 view is filled by the mapping)
  bool rmw = false;             // part of a read-modify-write (the read is followed by its write)
  bool plain = false;           // a plain (non-atomic) cell
  bool has_site = false;
  Site site = Site::kOwnerAnnounce;
  int rf = -1;             // reads: the event read from
  bool revisited = false;  // reads: given their write by a backward revisit (the explorer's maximality test)
  std::uint32_t stamp = 0;
  const char* file = "";
  unsigned line = 0;
};

struct Location {
  int initial = -1;     // the initial write's event
  std::vector<int> co;  // coherence order: write events, the initial write first
  bool plain = false;
  int creator = -1;  // the thread that created it (−1: before the threads started)
  int serial = 0;    // its rank among the creator's locations
};

struct Graph {
  std::vector<GraphEvent> events;
  std::vector<std::vector<int>> thread_events;  // program order per thread
  std::vector<Location> locations;
  std::uint32_t next_stamp = 1;

  int add(GraphEvent e) {
    e.stamp = next_stamp++;
    events.push_back(e);
    const int id = static_cast<int>(events.size()) - 1;
    if (e.thread >= 0) thread_events[static_cast<std::size_t>(e.thread)].push_back(id);
    return id;
  }
  // The position of write `w` in its location's coherence order.
  int co_position(int w) const {
    const auto& co = locations[static_cast<std::size_t>(events[w].location)].co;
    for (std::size_t i = 0; i < co.size(); ++i) {
      if (co[i] == w) return static_cast<int>(i);
    }
    return -1;
  }
  bool co_maximal(int w) const { return locations[static_cast<std::size_t>(events[w].location)].co.back() == w; }

  // Every event program-order or reads-from before one of `from` (those included): the porf-prefix.
  std::vector<bool> porf_prefix(const std::vector<int>& from) const {
    std::vector<bool> in(events.size(), false);
    std::vector<int> work;
    const auto reach = [&](int e) {
      if (e >= 0 && !in[e]) {
        in[e] = true;
        work.push_back(e);
      }
    };
    for (int e : from) reach(e);
    std::vector<int> position(events.size(), -1);
    for (const auto& list : thread_events) {
      for (std::size_t i = 0; i < list.size(); ++i) position[list[i]] = static_cast<int>(i);
    }
    while (!work.empty()) {
      const int e = work.back();
      work.pop_back();
      const GraphEvent& ev = events[e];
      if (ev.kind == ax::EventKind::read) reach(ev.rf);
      if (ev.thread >= 0 && position[e] > 0) reach(thread_events[ev.thread][position[e] - 1]);
    }
    return in;
  }

  // The graph of the events in `keep` (closed under program order and reads-from), renumbered.
  Graph restricted(const std::vector<bool>& keep, std::vector<int>& renumbered) const {
    Graph g;
    g.next_stamp = next_stamp;
    g.thread_events.resize(thread_events.size());
    renumbered.assign(events.size(), -1);
    for (std::size_t e = 0; e < events.size(); ++e) {
      if (!keep[e]) continue;
      renumbered[e] = static_cast<int>(g.events.size());
      g.events.push_back(events[e]);
    }
    for (GraphEvent& e : g.events) {
      if (e.rf >= 0) e.rf = renumbered[e.rf];
    }
    for (std::size_t t = 0; t < thread_events.size(); ++t) {
      for (int e : thread_events[t]) {
        if (keep[e]) g.thread_events[t].push_back(renumbered[e]);
      }
    }
    g.locations = locations;
    for (Location& l : g.locations) {
      l.initial = renumbered[l.initial];
      std::vector<int> co;
      for (int w : l.co) {
        if (renumbered[w] >= 0) co.push_back(renumbered[w]);
      }
      l.co = std::move(co);
    }
    return g;
  }
};

using WideExecution = ax::BasicExecution<ax::WideSet>;

// The graph as the axiomatic checker's execution (events in graph order; no dependencies: see explorer.hpp).
inline WideExecution as_execution(const Graph& g) {
  WideExecution x;
  const int n = static_cast<int>(g.events.size());
  x.event_count = n;
  x.events.reserve(g.events.size());
  using Rel = WideExecution::Rel;
  x.po = Rel(n), x.rmw = Rel(n), x.same_location = Rel(n), x.rf = Rel(n), x.co = Rel(n);
  x.addr = Rel(n), x.data = Rel(n), x.ctrl = Rel(n);
  x.value.assign(static_cast<std::size_t>(n), 0);
  for (int e = 0; e < n; ++e) {
    const GraphEvent& ev = g.events[e];
    x.events.push_back({ev.kind, ev.thread, 0, ev.location, ev.thread < 0 ? nullptr : &ev.instruction, ev.rmw});
    x.value[e] = static_cast<int>(ev.value.lo);
    if (ev.kind == ax::EventKind::read) ax::insert(x.reads, e), x.rf.add(ev.rf, e);
    if (ev.kind == ax::EventKind::write) ax::insert(x.writes, e);
    if (ev.kind == ax::EventKind::fence) ax::insert(x.fences, e);
    if (ev.thread < 0) ax::insert(x.initial, e);
  }
  // po, co and same-location as rows: each event's successors are the set of the events after it (built from the end).
  for (const auto& list : g.thread_events) {
    ax::WideSet later;
    for (std::size_t i = list.size(); i-- > 0;) {
      x.po.add_all(list[i], later);
      ax::insert(later, list[i]);
      if (i + 1 < list.size() && g.events[list[i]].rmw && g.events[list[i]].kind == ax::EventKind::read &&
          g.events[list[i + 1]].rmw && g.events[list[i + 1]].kind == ax::EventKind::write) {
        x.rmw.add(list[i], list[i + 1]);
      }
    }
  }
  std::vector<ax::WideSet> at(g.locations.size());
  for (std::size_t l = 0; l < g.locations.size(); ++l) {
    ax::WideSet later;
    for (std::size_t i = g.locations[l].co.size(); i-- > 0;) {
      x.co.add_all(g.locations[l].co[i], later);
      ax::insert(later, g.locations[l].co[i]);
    }
  }
  for (int e = 0; e < n; ++e) {
    if (g.events[e].location >= 0) ax::insert(at[static_cast<std::size_t>(g.events[e].location)], e);
  }
  for (int e = 0; e < n; ++e) {
    if (g.events[e].location >= 0) x.same_location.add_all(e, at[static_cast<std::size_t>(g.events[e].location)]);
  }
  return x;
}

}  // namespace frontsteal::graph
