// explorer.cpp — the exploration (explorer.hpp says what it explores and why it is enough).
#include "models_check/graph/explorer.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "models_check/axiomatic/models.hpp"
#include "models_check/graph/coherence_filter.hpp"
#include "models_check/graph/fiber.hpp"

namespace frontsteal::graph {

std::string_view name(GraphModel m) {
  switch (m) {
    case GraphModel::rc11: return "RC11";
    case GraphModel::armv8_ldar: return "ARMv8 (acquire → LDAR)";
    case GraphModel::armv8_ldapr: return "ARMv8.3 (acquire → LDAPR)";
  }
  return "?";
}

namespace {

enum class ThreadState : std::uint8_t { runnable, finished, blocked };

ax::Order to_order(Mo mo) {
  switch (mo) {
    case Mo::kRelaxed: return ax::Order::relaxed;
    case Mo::kAcquire: return ax::Order::acquire;
    case Mo::kRelease: return ax::Order::release;
    case Mo::kAcqRel: return ax::Order::acq_rel;
    case Mo::kSeqCst: return ax::Order::seq_cst;
  }
  return ax::Order::seq_cst;
}

struct Hash {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add(std::uint64_t v) {
    h ^= v;
    h *= 0x100000001b3ull;
    h ^= h >> 29;
  }
};

// Thrown through a fiber's frames? No: a fiber that must stop is suspended for good (Fiber says why). This marks
// the explorer's own "stop this run" decisions.
class Explorer {
 public:
  Explorer(Program& program, const ExploreOptions& options) : program_(program), options_(options) {}

  ExploreResult explore() {
    const auto start = std::chrono::steady_clock::now();
    auto last_progress = start;
    threads_ = program_.threads();
    for (int t = 0; t < threads_; ++t) fibers_.push_back(std::make_unique<Fiber>());
    Graph root;
    root.thread_events.resize(static_cast<std::size_t>(threads_));
    work_.push_back({nullptr, std::move(root)});
    std::uint64_t runs = 0;
    while (!work_.empty() && !stopped_) {
      Graph g = materialize(std::move(work_.back()));
      work_.pop_back();
      const std::size_t pushed_before = work_.size();
      run(std::move(g));
      // The run's forward alternatives share its final graph.
      const auto final_graph = std::make_shared<const Graph>(std::move(g_));
      for (std::size_t i = pushed_before; i < work_.size(); ++i) {
        if (work_[i].event >= 0) work_[i].run = final_graph;
      }
      ++runs;
      const auto now = std::chrono::steady_clock::now();
      const double seconds = std::chrono::duration<double>(now - start).count();
      if ((options_.max_executions != 0 && runs >= options_.max_executions) ||
          (options_.max_seconds > 0 && seconds >= options_.max_seconds)) {
        result_.bounded = !work_.empty();
        break;
      }
      if (options_.progress && now - last_progress >= std::chrono::seconds(1)) {
        last_progress = now;
        options_.progress(runs, result_.complete, work_.size(), seconds);
      }
    }
    result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result_);
  }

  // ---- the backend's calls --------------------------------------------------------------------------------
  int new_location(Value initial, bool plain) {
    const int creator = current_;
    const int serial = created_[static_cast<std::size_t>(creator + 1)]++;
    for (std::size_t l = 0; l < g_.locations.size(); ++l) {
      Location& loc = g_.locations[l];
      if (loc.creator == creator && loc.serial == serial) {
        if (creator < 0) g_.events[loc.initial].value = initial;
        return static_cast<int>(l);
      }
    }
    GraphEvent init;
    init.kind = ax::EventKind::write;
    init.location = static_cast<int>(g_.locations.size());
    init.value = initial;
    init.plain = plain;
    init.instruction.op = ax::Op::store;
    Location loc;
    loc.plain = plain;
    loc.creator = creator;
    loc.serial = serial;
    loc.initial = g_.add(init);
    loc.co.push_back(loc.initial);
    g_.locations.push_back(loc);
    return init.location;
  }

  Value load(int location, const Access& a) {
    if (current_ < 0) return main_context_read(location);
    await_turn();
    if (replaying()) return replay(ax::EventKind::read, location, a, false).value;
    return add_read(make_event(ax::EventKind::read, location, {}, ax::Op::load, a, false));
  }

  void store(int location, Value v, const Access& a) {
    if (current_ < 0) {
      if (threads_started_) throw std::logic_error("a store outside the threads after they started");
      g_.events[g_.locations[static_cast<std::size_t>(location)].initial].value = v;
      return;
    }
    await_turn();
    if (replaying()) {
      const GraphEvent& e = replay(ax::EventKind::write, location, a, false);
      if (!(e.value == v)) nondeterministic("a store wrote another value on replay");
      return;
    }
    add_write(make_event(ax::EventKind::write, location, v, ax::Op::store, a, false));
  }

  Value read_modify_write(int location, ax::Op op, const std::function<std::optional<Value>(Value)>& update,
                          const Access& a) {
    if (current_ < 0) {
      const Value old = main_context_read(location);
      if (const auto next = update(old)) store(location, *next, a);
      return old;
    }
    await_turn();
    Value old;
    int read_event = -1;
    if (replaying()) {
      const GraphEvent& e = replay(ax::EventKind::read, location, a, true);
      old = e.value;
      read_event = g_.thread_events[current_][replayed_[current_] - 1];
    } else {
      old = add_read(make_event(ax::EventKind::read, location, {}, op, a, true));
      read_event = g_.thread_events[current_].back();
    }
    const std::optional<Value> next = update(old);
    if (!next) {
      // A failed compare-exchange: only the read. It stays marked as an RMW's read for printing; atomicity
      // concerns only an rmw pair, which it is not part of.
      g_.events[read_event].rmw = false;
      return old;
    }
    await_turn();
    if (replaying()) {
      const GraphEvent& e = replay(ax::EventKind::write, location, a, true);
      if (!(e.value == *next)) nondeterministic("a read-modify-write wrote another value on replay");
      return old;
    }
    add_write(make_event(ax::EventKind::write, location, *next, op, a, true), g_.events[read_event].rf);
    return old;
  }

  void fence(ax::Order order, const Access& a) {
    if (current_ < 0) return;
    await_turn();
    GraphEvent e = make_event(ax::EventKind::fence, -1, {}, ax::Op::fence, a, false);
    e.instruction.order = order;
    e.instruction.arm = ax::armv8_view(e.instruction, false, options_.model == GraphModel::armv8_ldapr);
    if (replaying()) {
      (void)replay(ax::EventKind::fence, -1, a, false);
      return;
    }
    g_.add(e);
    result_.largest_graph = std::max(result_.largest_graph, g_.events.size());
  }

  std::size_t events_so_far() const { return current_ < 0 ? 0 : g_.thread_events[current_].size(); }

  [[noreturn]] void wait_failed(Site site) {
    if (current_ < 0) throw std::logic_error("a wait outside the threads");
    await_turn();
    if (replaying()) nondeterministic("a wait failed on replay before the thread's recorded events ran out");
    const int t = current_;
    // The failed iteration's reads: the last read, or for an idle round (A3) every read since the worker left
    // the active count (A2).
    const auto& list = g_.thread_events[t];
    std::size_t begin = list.size();
    if (site == Site::kActivePoll) {
      while (begin > 0 &&
             !(g_.events[list[begin - 1]].has_site && g_.events[list[begin - 1]].site == Site::kActiveLeave))
        --begin;
    } else {
      while (begin > 0 && g_.events[list[begin - 1]].kind != ax::EventKind::read) --begin;
      if (begin > 0) --begin;
    }
    wait_begin_[t] = begin;
    wait_site_[t] = site;
    end_run_if_blocked_for_good(t);
    leave_thread(ThreadState::blocked);
  }

  // Blocks the thread rather than end the run: a write still to come may revisit the read that made `holds` false.
  void assume(bool holds) {
    if (holds) return;
    assumed_false_[current_] = true;
    end_run_if_blocked_for_good(current_);
    leave_thread(ThreadState::blocked);
  }

  [[noreturn]] void fail(Verdict v, const std::string& what, const char* file, unsigned line) {
    {
      std::ostringstream s;
      s << what << " (thread " << current_ << ", " << file << ":" << line << ")";
      record_failure({v, s.str()});
    }
    leave_thread(ThreadState::blocked);
  }

 private:
  bool replaying() const { return replayed_[current_] < prefix_[current_]; }

  // Replay runs the recorded events in the order they were added (stamps), one thread at a time, so the program's
  // own unmodelled memory (the frame loop's plain fields handed over between threads, ordered by the protocol's
  // synchronisation) holds what it held when the graph was built. Every backend call waits here for its turn.
  void await_turn() {
    while (replay_phase_ && turn_ != current_) fibers_[current_]->suspend();
    turn_ = -1;
  }

  Value main_context_read(int location) const {
    const Location& loc = g_.locations[static_cast<std::size_t>(location)];
    return g_.events[threads_started_ ? loc.co.back() : loc.initial].value;
  }

  GraphEvent make_event(ax::EventKind kind, int location, Value v, ax::Op op, const Access& a, bool rmw) const {
    GraphEvent e;
    e.kind = kind;
    e.thread = current_;
    e.location = location;
    e.value = v;
    e.rmw = rmw;
    e.plain = a.plain;
    e.has_site = a.has_site;
    e.site = a.site;
    e.file = a.file;
    e.line = a.line;
    e.instruction.op = op;
    e.instruction.location = location;
    e.instruction.order = to_order(a.order);
    if (a.has_site) e.instruction.label = std::string(info(a.site).label);
    e.instruction.arm = ax::armv8_view(e.instruction, false, options_.model == GraphModel::armv8_ldapr);
    return e;
  }

  // The exploration bound (ExploreOptions::bounded_site): past it, the run is cut.
  void enforce_bound(const Access& a) {
    if (!options_.bound || !a.has_site || a.site != options_.bounded_site) return;
    int count = 0;
    for (const GraphEvent& e : g_.events)
      count += e.has_site && e.site == a.site && e.kind != ax::EventKind::read ? 1 : 0;
    if (count >= options_.bound) {
      // Block the thread rather than abandon the run: revisits by the other threads' later writes still happen, so
      // an execution within the bound whose canonical path passes here is still reached.
      bound_blocked_[current_] = true;
      end_run_if_blocked_for_good(current_);
      leave_thread(ThreadState::blocked);
    }
  }

  const GraphEvent& replay(ax::EventKind kind, int location, const Access& a, bool rmw) {
    const int id = g_.thread_events[current_][replayed_[current_]++];
    const GraphEvent& e = g_.events[id];
    if (e.kind != kind || e.location != location || e.rmw != rmw || e.has_site != a.has_site ||
        (a.has_site && e.site != a.site)) {
      // A failed compare-exchange's read is recorded with rmw cleared (read_modify_write).
      if (!(kind == ax::EventKind::read && rmw && !e.rmw && e.kind == kind && e.location == location)) {
        nondeterministic("the thread asked for another access than the one recorded");
      }
    }
    return e;
  }

  // A replay that does not retrace its graph: the program depends on something other than the values it read
  // (a clock, an address, a static counter). The exploration stops with the error.
  [[noreturn]] void nondeterministic(const char* what) {
    const std::string text = std::string("the program is not deterministic: ") + what;
    if (current_ < 0) throw std::logic_error("graph explorer: " + text);
    if (result_.outcome.verdict == Verdict::kPass) {
      result_.outcome = {Verdict::kOtherFailure, text};
      result_.witness = describe(g_);
    }
    stopped_ = true;
    leave_thread(ThreadState::blocked);
  }

  // The model's own axioms on the whole graph: every run that ends, fails or hangs is judged by them.
  bool consistent(const Graph& g) const {
    const WideExecution x = as_execution(g);
    return options_.model == GraphModel::rc11 ? ax::rc11_consistent(x, true) : ax::armv8_consistent(x);
  }

  void set_rf(Graph& g, int read, int write) {
    g.events[read].rf = write;
    g.events[read].value = g.events[write].value;
  }

  // The options the filter lets through; none (the prefix was inconsistent after all): the run is abandoned.
  //
  // A thread leaves (leave_thread) only from frames that own no heap memory: its stack is dropped without
  // destructors (fiber.hpp), so add_read and add_write leave after their working parts have returned.
  template <class T, class Pass>
  std::vector<T> passing(const std::vector<T>& options, Pass&& pass) {
    std::vector<T> ok;
    for (const T& option : options) {
      if (pass(option)) {
        ok.push_back(option);
      } else {
        ++result_.inconsistent;
      }
    }
    if (ok.empty()) dead_ = true;  // the caller leaves the thread once its own locals are gone
    return ok;
  }

  // A new read: one branch per consistent write; this run continues with the coherence-latest.
  Value add_read(GraphEvent e) {
    const bool added = try_add_read(std::move(e));
    if (!added) leave_thread(ThreadState::blocked);
    return g_.events[g_.thread_events[current_].back()].value;
  }
  bool try_add_read(GraphEvent e) {
    const int id = g_.add(e);
    result_.largest_graph = std::max(result_.largest_graph, g_.events.size());
    const std::vector<int> candidates = g_.locations[static_cast<std::size_t>(e.location)].co;
    const CoherenceFilter filter(g_);
    const std::vector<int> ok = passing(candidates, [&](int w) { return filter.read_ok(id, w); });
    if (ok.empty()) return false;
    for (std::size_t i = 0; i + 1 < ok.size(); ++i) work_.push_back(forward(id, ok[i], 0));
    set_rf(g_, id, ok.back());
    return true;
  }

  // A new write: one branch per consistent coherence place (an RMW's write goes right after the write its read
  // read), and one per read it can revisit; this run continues with the write coherence-last.
  void add_write(GraphEvent e, int after = -1) {
    enforce_bound({false, Mo::kRelaxed, e.has_site, e.site, "", 0});
    const bool added = try_add_write(std::move(e), after);
    if (!added) leave_thread(ThreadState::blocked);
  }
  bool try_add_write(GraphEvent e, int after) {
    const int t = current_;
    const auto& mine = g_.thread_events[t];
    std::vector<bool> prefix =
        mine.empty() ? std::vector<bool>(g_.events.size(), false) : g_.porf_prefix({mine.back()});
    for (const Location& l : g_.locations) prefix[l.initial] = true;
    const std::size_t location = static_cast<std::size_t>(e.location);

    // Revisits, from the graph without the write.
    const std::size_t before = options_.defect == ExplorerDefect::no_revisits ? 0 : g_.events.size();
    for (std::size_t r = 0; r < before; ++r) {
      const GraphEvent& read = g_.events[r];
      if (read.kind != ax::EventKind::read || read.location != e.location || prefix[r]) continue;
      revisit(static_cast<int>(r), e, prefix);
    }

    const int id = g_.add(e);
    result_.largest_graph = std::max(result_.largest_graph, g_.events.size());
    std::vector<int> co = g_.locations[location].co;
    std::vector<std::size_t> places;
    if (after >= 0) {
      places.push_back(static_cast<std::size_t>(std::find(co.begin(), co.end(), after) - co.begin()) + 1);
    } else if (options_.defect == ExplorerDefect::co_last_only) {
      places.push_back(co.size());
    } else {
      for (std::size_t p = 1; p <= co.size(); ++p) places.push_back(p);
    }
    const CoherenceFilter filter(g_);
    const std::vector<std::size_t> ok = passing(places, [&](std::size_t p) { return filter.write_ok(id, p); });
    if (ok.empty()) return false;
    for (std::size_t i = 0; i + 1 < ok.size(); ++i) work_.push_back(forward(id, -1, ok[i]));
    std::vector<int> placed = co;
    placed.insert(placed.begin() + static_cast<std::ptrdiff_t>(ok.back()), id);
    g_.locations[location].co = std::move(placed);
    return true;
  }

  // Read `r` (not in the new write's porf-prefix) reads from the new write `w`: keep what was added before r and
  // w's prefix, add w, then r (so every rf and po edge still runs from a smaller stamp to a larger one).
  void revisit(int r, const GraphEvent& w, const std::vector<bool>& prefix) {
    if (options_.defect != ExplorerDefect::no_maximality && !maximal_extension(r, prefix)) {
      ++result_.revisits_not_maximal;
      return;
    }
    const std::uint32_t cut = g_.events[r].stamp;
    std::vector<bool> keep(g_.events.size(), false);
    for (std::size_t e = 0; e < g_.events.size(); ++e) keep[e] = prefix[e] || g_.events[e].stamp < cut;
    keep[r] = true;
    std::vector<int> renumbered;
    Graph g = g_.restricted(keep, renumbered);
    const int read = renumbered[r];
    const int write = g.add(w);
    g.events[read].stamp = g.next_stamp++;
    g.events[read].revisited = true;
    set_rf(g, read, write);
    const std::size_t location = static_cast<std::size_t>(w.location);
    std::vector<int> co = g.locations[location].co;
    std::vector<std::size_t> places;
    if (w.rmw) {
      // The RMW's own read is the thread's event before w; its write goes right after what that read read.
      const auto& mine = g.thread_events[static_cast<std::size_t>(w.thread)];
      const int own_read = mine[mine.size() - 2];
      places.push_back(static_cast<std::size_t>(std::find(co.begin(), co.end(), g.events[own_read].rf) - co.begin()) +
                       1);
    } else {
      for (std::size_t p = 1; p <= co.size(); ++p) places.push_back(p);
    }
    const CoherenceFilter filter(g);
    for (std::size_t p : places) {
      if (!filter.write_ok(write, p)) {
        ++result_.inconsistent;
        continue;
      }
      std::vector<int> placed = co;
      placed.insert(placed.begin() + static_cast<std::ptrdiff_t>(p), write);
      g.locations[location].co = placed;
      if (!filter.read_ok(read, write)) {
        g.locations[location].co = co;
        ++result_.inconsistent;
        continue;
      }
      if (!explored_revisits_.insert(hash(g, true)).second) {
        ++result_.revisits_repeated;
        continue;
      }
      ++result_.revisits;
      work_.push_back({nullptr, g});
      g.locations[location].co = co;
    }
  }

  // TruSt's maximality condition (Kokologiannakis et al., POPL 2022, §5). Revisiting r deletes D = the events added
  // after r and outside the new write's porf-prefix P. Every graph that differs from this one only in D and in what
  // r read revisits to the same graph; the revisit is taken from one of them only: the one in which r and every
  // event of D were added MAXIMALLY with respect to Prev(e) = {events added before e} ∪ P:
  //   a read    reads the coherence-latest write of its location in Prev(e);
  //   a write   is coherence-after every write of its location in Prev(e);
  //   a read that a revisit gave its write counts as added where it first ran, before that write, so it is maximal
  //             only if its write is in P (TruSt keeps it there; this explorer re-adds it after its write, and
  //             Prev(e) agrees with TruSt's once its write is in P, since everything added in between is too).
  bool maximal_extension(int r, const std::vector<bool>& prefix) const {
    const std::uint32_t cut = g_.events[r].stamp;
    const auto deleted = [&](int e) { return g_.events[e].stamp > cut && !prefix[e]; };
    // A write after `w` in its location's coherence order that is in Prev(e).
    const auto newer_in_prev = [&](int w, int e) {
      const auto& co = g_.locations[static_cast<std::size_t>(g_.events[w].location)].co;
      for (auto it = std::find(co.begin(), co.end(), w) + 1; it < co.end(); ++it) {
        if (g_.events[*it].stamp < g_.events[e].stamp || prefix[*it]) return true;
      }
      return false;
    };
    for (std::size_t i = 0; i < g_.events.size(); ++i) {
      const int e = static_cast<int>(i);
      const GraphEvent& ev = g_.events[i];
      if (ev.thread < 0 || (e != r && !deleted(e))) continue;
      if (ev.kind == ax::EventKind::read) {
        if (ev.revisited && !prefix[ev.rf]) return false;
        if (newer_in_prev(ev.rf, e)) return false;
      } else if (ev.kind == ax::EventKind::write) {
        if (newer_in_prev(e, e)) return false;
      }
    }
    return true;
  }

  // Thread t stops here (a failed wait, a false assumption, the bound) right after reading, last, a write that a
  // write added before the read already follows in coherence. No branch of this run can complete it: a later revisit
  // that deletes that read needs it maximal (maximal_extension) and it is not, nor can the read itself be revisited;
  // a branch that keeps it keeps the thread's whole prefix, so the thread stops at the same place again. The run
  // ends now instead of running the other threads on for nothing (the branches already taken stay).
  void end_run_if_blocked_for_good(int t) {
    if (options_.defect == ExplorerDefect::no_maximality) return;  // the argument rests on the condition
    const auto& list = g_.thread_events[t];
    for (auto it = list.rbegin(); it != list.rend(); ++it) {
      const GraphEvent& e = g_.events[*it];
      if (e.kind != ax::EventKind::read) continue;
      const auto& co = g_.locations[static_cast<std::size_t>(e.location)].co;
      for (auto w = std::find(co.begin(), co.end(), e.rf) + 1; w < co.end(); ++w) {
        if (g_.events[*w].stamp < e.stamp) {
          ++result_.ended_early;
          dead_ = true;
          return;
        }
      }
      return;
    }
  }

  [[noreturn]] void leave_thread(ThreadState s) {
    state_[current_] = s;
    fibers_[current_]->suspend();
    throw std::logic_error("graph explorer: a thread that left was resumed");
  }

  void record_failure(Outcome o) {
    if (result_.outcome.verdict != Verdict::kPass) return;
    if (!consistent(g_)) {  // the filter let an inconsistent prefix through: no execution fails here
      ++result_.inconsistent_runs;
      dead_ = true;
      return;
    }
    result_.outcome = std::move(o);
    result_.witness = describe(g_);
    if (options_.stop_at_failure) stopped_ = true;
  }

  std::uint64_t hash(const Graph& g, bool with_stamps) const {
    std::vector<std::pair<int, int>> where(g.events.size());
    for (std::size_t t = 0; t < g.thread_events.size(); ++t) {
      for (std::size_t i = 0; i < g.thread_events[t].size(); ++i) {
        where[g.thread_events[t][i]] = {static_cast<int>(t), static_cast<int>(i)};
      }
    }
    for (std::size_t l = 0; l < g.locations.size(); ++l) where[g.locations[l].initial] = {-1, static_cast<int>(l)};
    Hash h;
    for (std::size_t t = 0; t < g.thread_events.size(); ++t) {
      h.add(0xfeedull + t);
      for (int e : g.thread_events[t]) {
        const GraphEvent& ev = g.events[e];
        h.add(static_cast<std::uint64_t>(ev.kind) | static_cast<std::uint64_t>(ev.location + 1) << 8);
        h.add(ev.value.lo);
        h.add(ev.value.hi);
        if (with_stamps) h.add(ev.revisited ? 1 : 0);
        if (ev.rf >= 0)
          h.add(static_cast<std::uint64_t>(where[ev.rf].first + 1) << 32 |
                static_cast<std::uint32_t>(where[ev.rf].second));
      }
    }
    for (const Location& l : g.locations) {
      h.add(0xc0ull);
      for (int w : l.co)
        h.add(static_cast<std::uint64_t>(where[w].first + 1) << 32 | static_cast<std::uint32_t>(where[w].second));
    }
    if (with_stamps) {
      std::vector<int> order(g.events.size());
      for (std::size_t e = 0; e < order.size(); ++e) order[e] = static_cast<int>(e);
      std::sort(order.begin(), order.end(), [&](int a, int b) { return g.events[a].stamp < g.events[b].stamp; });
      for (int e : order)
        h.add(static_cast<std::uint64_t>(where[e].first + 1) << 32 | static_cast<std::uint32_t>(where[e].second));
    }
    return h.h;
  }

  void run(Graph g) {
    g_ = std::move(g);
    prefix_.assign(static_cast<std::size_t>(threads_), 0);
    for (int t = 0; t < threads_; ++t) prefix_[t] = g_.thread_events[t].size();
    replayed_.assign(static_cast<std::size_t>(threads_), 0);
    state_.assign(static_cast<std::size_t>(threads_), ThreadState::runnable);
    wait_begin_.assign(static_cast<std::size_t>(threads_), 0);
    wait_site_.assign(static_cast<std::size_t>(threads_), Site::kOwnerAnnounce);
    created_.assign(static_cast<std::size_t>(threads_ + 1), 0);
    dead_ = false;
    bound_blocked_.assign(static_cast<std::size_t>(threads_), false);
    assumed_false_.assign(static_cast<std::size_t>(threads_), false);
    threads_started_ = false;
    current_ = -1;
    program_.setup();
    threads_started_ = true;
    for (int t = 0; t < threads_; ++t) {
      fibers_[t]->start([this, t] {
        try {
          program_.run_thread(t);
        } catch (const std::exception& ex) {  // an exception must not unwind past the fiber's entry
          record_failure({Verdict::kOtherFailure, std::string("thread threw: ") + ex.what()});
          dead_ = dead_ || !stopped_;  // discarded (inconsistent) or not stopping: this run ends here
        }
      });
    }
    // Replay: the recorded events, in stamp order.
    replay_phase_ = true;
    while (!stopped_ && !dead_) {
      int next = -1;
      std::uint32_t lowest = 0;
      for (int t = 0; t < threads_; ++t) {
        if (replayed_[t] >= prefix_[t] || fibers_[t]->finished() || state_[t] != ThreadState::runnable) continue;
        const std::uint32_t stamp = g_.events[g_.thread_events[t][replayed_[t]]].stamp;
        if (next < 0 || stamp < lowest) next = t, lowest = stamp;
      }
      if (next < 0) break;
      turn_ = next;
      resume(next);
    }
    replay_phase_ = false;
    // Extension: the lowest-numbered thread that can run runs until it finishes or blocks.
    for (int t = 0; t < threads_ && !stopped_ && !dead_; ++t) {
      if (state_[t] == ThreadState::runnable && !fibers_[t]->finished()) resume(t);
    }
    for (int t = 0; t < threads_ && !stopped_ && !dead_; ++t) {
      if (replayed_[t] != prefix_[t]) nondeterministic("a thread stopped before its recorded events ran out");
    }
    if (!stopped_ && !dead_) finish();
    program_.teardown();
  }

  void resume(int t) {
    current_ = t;
    fibers_[t]->resume();
    current_ = -1;
    if (fibers_[t]->finished()) state_[t] = ThreadState::finished;
  }

  void finish() {
    if (std::find(bound_blocked_.begin(), bound_blocked_.end(), true) != bound_blocked_.end()) {
      ++result_.cut;
      return;
    }
    if (std::find(assumed_false_.begin(), assumed_false_.end(), true) != assumed_false_.end()) {
      ++result_.blocked;
      return;
    }
    bool any_blocked = false, all_stuck = true;
    for (int t = 0; t < threads_; ++t) {
      if (state_[t] != ThreadState::blocked) continue;
      any_blocked = true;
      const auto& list = g_.thread_events[t];
      for (std::size_t i = wait_begin_[t]; i < list.size(); ++i) {
        const GraphEvent& e = g_.events[list[i]];
        if (e.kind == ax::EventKind::read && could_read_newer(list[i])) all_stuck = false;
      }
    }
    if (any_blocked && !all_stuck) {
      ++result_.blocked;
      return;
    }
    if (any_blocked) {
      ++result_.hangs;
      std::ostringstream s;
      s << "a wait nothing can satisfy:";
      for (int t = 0; t < threads_; ++t) {
        if (state_[t] == ThreadState::blocked) s << " thread " << t << " at " << info(wait_site_[t]).label;
      }
      record_failure({Verdict::kDeadlock, s.str()});
      return;
    }
    if (options_.defect != ExplorerDefect::no_final_check && !consistent(g_)) {
      ++result_.inconsistent_runs;
      return;
    }
    ++result_.complete;
    if (explored_complete_.insert(hash(g_, false)).second) ++result_.distinct;
    // The program's own check first: a duplicate run also races on its payload, and the duplicate is the finding.
    if (Outcome o = program_.check(g_); o.verdict != Verdict::kPass) {
      record_failure(std::move(o));
      return;
    }
    if (options_.model == GraphModel::rc11) {
      if (std::string race = data_race(); !race.empty()) record_failure({Verdict::kDataRace, race});
    }
  }

  // A write of another thread follows the one read `r` read in coherence order: a branch in which r reads it
  // exists. (Writes of r's own thread after r cannot be read by r.)
  bool could_read_newer(int r) const {
    const GraphEvent& read = g_.events[r];
    const auto& co = g_.locations[static_cast<std::size_t>(read.location)].co;
    const auto at = std::find(co.begin(), co.end(), read.rf);
    for (auto it = at + 1; it < co.end(); ++it) {
      if (g_.events[*it].thread != read.thread) return true;
    }
    return false;
  }

  // RC11: two accesses to a plain cell from different threads, at least one a write, not ordered by hb.
  std::string data_race() const {
    bool any_plain = false;
    for (const Location& l : g_.locations) any_plain = any_plain || l.plain;
    if (!any_plain) return {};
    const WideExecution x = as_execution(g_);
    const auto hb = ax::rc11_happens_before(x);
    for (std::size_t a = 0; a < g_.events.size(); ++a) {
      const GraphEvent& ea = g_.events[a];
      if (ea.thread < 0 || !ea.plain || ea.location < 0) continue;
      for (std::size_t b = a + 1; b < g_.events.size(); ++b) {
        const GraphEvent& eb = g_.events[b];
        if (eb.thread < 0 || eb.thread == ea.thread || eb.location != ea.location) continue;
        if (ea.kind != ax::EventKind::write && eb.kind != ax::EventKind::write) continue;
        if (hb.has(static_cast<int>(a), static_cast<int>(b)) || hb.has(static_cast<int>(b), static_cast<int>(a)))
          continue;
        std::ostringstream s;
        s << "data race on a plain cell: e" << a << " (thread " << ea.thread << ", " << ea.file << ":" << ea.line
          << ") and e" << b << " (thread " << eb.thread << ", " << eb.file << ":" << eb.line << ")";
        return s.str();
      }
    }
    return {};
  }

  Program& program_;
  ExploreOptions options_;
  ExploreResult result_;
  int threads_ = 0;
  std::vector<std::unique_ptr<Fiber>> fibers_;
  // A branch still to explore. A forward alternative (another write for a new read, another coherence place for a
  // new write) is the choice alone: the graph it branches from is its run's final graph cut back to the events
  // added up to the choosing event (every later event has a later stamp), and all of a run's alternatives share
  // that one graph. A revisit's graph (and the root) is kept whole.
  struct Branch {
    std::shared_ptr<const Graph> run;  // forward: the final graph of the run that made the choice
    Graph graph;                       // otherwise: the graph itself
    int event = -1;                    // forward: the choosing event, in `run`
    int rf = -1;                       // forward read: the write it reads instead, in `run`
    std::size_t co_place = 0;          // forward write: its place among the location's other writes
  };
  std::vector<Branch> work_;

  // The branch in which new event `event` of g_ reads `rf` instead (a read) or takes coherence place `co_place`
  // (a write); its `run` is filled in when the run ends.
  Branch forward(int event, int rf, std::size_t co_place) const {
    Branch b;
    b.event = event;
    b.rf = rf;
    b.co_place = co_place;
    return b;
  }

  Graph materialize(Branch&& b) const {
    if (b.event < 0) return std::move(b.graph);
    const Graph& base = *b.run;
    const std::uint32_t up_to = base.events[b.event].stamp;
    std::vector<bool> keep(base.events.size());
    for (std::size_t e = 0; e < keep.size(); ++e) keep[e] = base.events[e].stamp <= up_to;
    std::vector<int> renumbered;
    Graph g = base.restricted(keep, renumbered);
    g.next_stamp = up_to + 1;
    const int e = renumbered[b.event];
    if (g.events[e].kind == ax::EventKind::read) {
      g.events[e].rf = renumbered[b.rf];
      g.events[e].value = g.events[g.events[e].rf].value;
    } else {
      auto& co = g.locations[static_cast<std::size_t>(g.events[e].location)].co;
      co.erase(std::find(co.begin(), co.end(), e));
      co.insert(co.begin() + static_cast<std::ptrdiff_t>(b.co_place), e);
    }
    return g;
  }
  std::unordered_set<std::uint64_t> explored_revisits_, explored_complete_;
  bool stopped_ = false;

  // The current run.
  Graph g_;
  std::vector<std::size_t> prefix_, replayed_, wait_begin_;
  std::vector<Site> wait_site_;
  std::vector<ThreadState> state_;
  std::vector<int> created_;
  int current_ = -1;
  bool dead_ = false;  // a choice had no consistent option: the run is abandoned
  bool threads_started_ = false;
  bool replay_phase_ = false;
  std::vector<bool> bound_blocked_;  // per thread: stopped at the exploration bound
  std::vector<bool> assumed_false_;  // per thread: stopped by a false assumption
  int turn_ = -1;                    // replay: the thread whose recorded event is next
};

Explorer* g_explorer = nullptr;

Explorer& current() {
  if (g_explorer == nullptr) throw std::logic_error("graph backend used outside graph::explore");
  return *g_explorer;
}

}  // namespace

ExploreResult explore(Program& program, const ExploreOptions& options) {
  // Every consistency check allocates relations of a few tens of kilobytes; without these, glibc returns the top of
  // the heap to the kernel after each and the brk calls (with their TLB shootdowns) cost more than the checks.
  mallopt(M_TRIM_THRESHOLD, 256 * 1024 * 1024);
  mallopt(M_TOP_PAD, 64 * 1024 * 1024);
  Explorer explorer(program, options);
  Explorer* const outer = g_explorer;
  g_explorer = &explorer;
  struct Restore {
    Explorer* outer;
    ~Restore() { g_explorer = outer; }
  } restore{outer};
  return explorer.explore();
}

namespace runtime {
int new_location(Value initial, bool plain) { return current().new_location(initial, plain); }
Value load(int location, const Access& a) { return current().load(location, a); }
void store(int location, Value v, const Access& a) { current().store(location, v, a); }
Value read_modify_write(int location, ax::Op op, const std::function<std::optional<Value>(Value)>& update,
                        const Access& a) {
  return current().read_modify_write(location, op, update, a);
}
void fence(ax::Order order, const Access& a) { current().fence(order, a); }
std::size_t events_so_far() { return current().events_so_far(); }
void assume(bool holds) { current().assume(holds); }
void wait_failed(Site site) { current().wait_failed(site); }
void fail(Verdict v, const std::string& what, const char* file, unsigned line) { current().fail(v, what, file, line); }
}  // namespace runtime

std::string describe(const Graph& g) {
  static constexpr const char* kOrder[] = {"rlx", "acq", "rel", "acq_rel", "sc"};
  std::ostringstream s;
  const auto event = [&](int id) {
    const GraphEvent& e = g.events[id];
    std::ostringstream o;
    o << "e" << id << " ";
    if (e.thread < 0) {
      o << "init loc" << e.location << "=" << e.value.lo;
      return o.str();
    }
    switch (e.kind) {
      case ax::EventKind::read: o << (e.rmw ? "RMW-R " : "R ") << "loc" << e.location << "=" << e.value.lo; break;
      case ax::EventKind::write: o << (e.rmw ? "RMW-W " : "W ") << "loc" << e.location << "=" << e.value.lo; break;
      case ax::EventKind::fence: o << "F"; break;
    }
    o << " (" << (e.plain ? "plain" : kOrder[static_cast<int>(e.instruction.order)]) << ")";
    if (e.has_site) o << " [" << info(e.site).label << " " << info(e.site).name << "]";
    if (e.kind == ax::EventKind::read) o << " rf←e" << e.rf;
    std::string file = e.file;
    if (const auto cut = file.rfind("/core/"); cut != std::string::npos) file = file.substr(cut + 1);
    if (const auto cut = file.rfind("/models_check/"); cut != std::string::npos) file = file.substr(cut + 1);
    o << "  " << file << ":" << e.line;
    return o.str();
  };
  for (std::size_t t = 0; t < g.thread_events.size(); ++t) {
    s << "  thread " << t << ":\n";
    for (int e : g.thread_events[t]) s << "    " << event(e) << "\n";
  }
  s << "  co (per location, initial write first):\n";
  for (std::size_t l = 0; l < g.locations.size(); ++l) {
    if (g.locations[l].co.size() < 2) continue;
    s << "    loc" << l << ":";
    for (int w : g.locations[l].co) s << " e" << w;
    s << "\n";
  }
  return s.str();
}

}  // namespace frontsteal::graph
