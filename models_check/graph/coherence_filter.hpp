// coherence_filter.hpp — a fast necessary condition for consistency, applied at every choice of the explorer; the
// memory model's own axioms (models_check/axiomatic/models.hpp) still judge every run at its end.
//
// RC11's coherence (hb ; eco? irreflexive) at the newest event e, which has no outgoing hb edge yet:
//   a read may not read a write coherence-before one that happens before it, or before the write that a read that
//   happens before it read;
//   a write goes coherence-after every write that happens before it and every write read by a read that does;
// and atomicity: no write may be placed between an RMW's read's write and the RMW's own write.
// hb = (po ∪ sw)+ is computed along the explorer's addition order (a linearization of po ∪ rf, hence of hb) with
// RC11's release sequences and fences (models.hpp's rs and sw). Why the filter is also sound for ARMv8: on
// executions with po ∪ rf acyclic the standard mapping is correct (Podkopaev, Lahav, Vafeiadis, POPL 2019), so
// every ARMv8-consistent execution of the compiled program is RC11-consistent and passes this filter.
#pragma once

#include <algorithm>
#include <numeric>
#include <vector>

#include "models_check/graph/execution_graph.hpp"

namespace frontsteal::graph {

class CoherenceFilter {
 public:
  // Computes the happens-before predecessors of every event of `g`.
  explicit CoherenceFilter(const Graph& g) : g_(g), before_(g.events.size()), position_(g.events.size(), -1) {
    for (const auto& list : g.thread_events) {
      for (std::size_t i = 0; i < list.size(); ++i) position_[list[i]] = static_cast<int>(i);
    }
    std::vector<int> order(g.events.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return g.events[a].stamp < g.events[b].stamp; });
    for (int e : order) before_[e] = compute(e, g.events[e].rf);
  }

  // May `read` (the newest event of its thread) read from `write`?
  bool read_ok(int read, int write) const {
    const ax::WideSet h = compute(read, write);
    return co_of(write) >= latest_seen(h, g_.events[read].location);
  }
  // May `write` (the newest event of its thread, not yet in its location's coherence order) take place `place`
  // (an insertion index into that order)?
  bool write_ok(int write, std::size_t place) const {
    const int location = g_.events[write].location;
    if (static_cast<int>(place) <= latest_seen(compute(write, -1), location)) return false;
    const auto& co = g_.locations[static_cast<std::size_t>(location)].co;
    if (place < co.size()) {  // between co[place-1] and co[place]: not inside another RMW
      const GraphEvent& next = g_.events[co[place]];
      if (next.rmw && co[place] != write) {
        const auto& list = g_.thread_events[static_cast<std::size_t>(next.thread)];
        const int read = list[static_cast<std::size_t>(position_[co[place]] - 1)];
        if (g_.events[read].rf == co[place - 1]) return false;
      }
    }
    return true;
  }

 private:
  bool releases(const GraphEvent& e) const {
    const ax::Order o = e.instruction.order;
    return e.kind != ax::EventKind::read && !e.plain &&
           (o == ax::Order::release || o == ax::Order::acq_rel || o == ax::Order::seq_cst);
  }
  bool acquires(const GraphEvent& e) const {
    const ax::Order o = e.instruction.order;
    return e.kind != ax::EventKind::write && !e.plain &&
           (o == ax::Order::acquire || o == ax::Order::acq_rel || o == ax::Order::seq_cst);
  }
  int co_of(int w) const {
    const auto& co = g_.locations[static_cast<std::size_t>(g_.events[w].location)].co;
    return static_cast<int>(std::find(co.begin(), co.end(), w) - co.begin());
  }
  void add_with_past(ax::WideSet& h, int e) const {
    h |= before_[e];
    ax::insert(h, e);
  }
  // sw into an acquire from write w: the heads of w's release sequence (rs), following rf;rmw back.
  void synchronize(ax::WideSet& h, int w) const {
    for (int x = w; x >= 0;) {
      const GraphEvent& ex = g_.events[x];
      if (ex.thread < 0) return;
      const auto& list = g_.thread_events[static_cast<std::size_t>(ex.thread)];
      bool write_head = false, fence_head = false;
      for (int i = position_[x]; i >= 0 && !(write_head && fence_head); --i) {
        const int c = list[static_cast<std::size_t>(i)];
        const GraphEvent& ec = g_.events[c];
        if (!write_head && ec.kind == ax::EventKind::write && ec.location == ex.location && releases(ec)) {
          add_with_past(h, c), write_head = true;
        }
        if (!fence_head && ec.kind == ax::EventKind::fence && releases(ec) && i < position_[x]) {
          add_with_past(h, c), fence_head = true;
        }
      }
      if (!ex.rmw) return;
      x = g_.events[list[static_cast<std::size_t>(position_[x] - 1)]].rf;  // the RMW's read's write
    }
  }
  // hb-predecessors of e (e's rf taken as `rf`).
  ax::WideSet compute(int e, int rf) const {
    ax::WideSet h;
    const GraphEvent& ev = g_.events[e];
    if (ev.thread < 0) return h;
    const auto& list = g_.thread_events[static_cast<std::size_t>(ev.thread)];
    const int at = position_[e];
    if (at > 0) add_with_past(h, list[static_cast<std::size_t>(at - 1)]);
    if (ev.kind == ax::EventKind::read && acquires(ev) && rf >= 0) synchronize(h, rf);
    if (ev.kind == ax::EventKind::fence && acquires(ev)) {
      for (int i = 0; i < at; ++i) {
        const GraphEvent& r = g_.events[list[static_cast<std::size_t>(i)]];
        if (r.kind == ax::EventKind::read && r.rf >= 0 && !r.plain) synchronize(h, r.rf);
      }
    }
    return h;
  }
  // The coherence position of the latest write at `location` that h holds or that a read in h read.
  int latest_seen(const ax::WideSet& h, int location) const {
    int latest = 0;
    ax::for_each(h, [&](int x) {
      const GraphEvent& ex = g_.events[x];
      if (ex.location != location) return;
      const int w = ex.kind == ax::EventKind::read ? ex.rf : x;
      if (w >= 0) latest = std::max(latest, co_of(w));
    });
    return latest;
  }

  const Graph& g_;
  std::vector<ax::WideSet> before_;
  std::vector<int> position_;
};

}  // namespace frontsteal::graph
