// graph_backend.hpp — the atomics backend that runs core/ inside the execution-graph explorer (explorer.hpp).
//
// Every atomic and every plain cell is a location of the execution graph; every call is an event carrying the
// site's label, its C++ order and the protocol's own source line, so a counterexample names core/'s lines. The
// value a load returns is the value of the write the explorer chose for it.
// Modelling choices (as the Relacy backend's, relacy_backend.hpp):
//   - plain cells are non-atomic locations: under RC11 two accesses not ordered by happens-before, one a write,
//     are a data race, reported;
//   - Fence::kCompiler is no event (the explorer never reorders a thread's own program order); the asymmetric
//     pair (a compiler fence on the owner, membarrier on the thief) is a seq_cst fence on both sides, which is the
//     guarantee membarrier(PRIVATE_EXPEDITED) gives the pair;
//   - a wait's failed iteration (spin_pause, wait_while_equal) blocks the thread: spin-assume (explorer.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/memory_order.hpp"
#include "core/site.hpp"
#include "core/source_location.hpp"
#include "models_check/graph/explorer.hpp"

namespace frontsteal::graph {

template <class T>
class GraphAtomic {
 public:
  GraphAtomic(T initial = T{})
      : location_(runtime::new_location(encode(initial), false)) {}  // NOLINT: like std::atomic
  GraphAtomic(const GraphAtomic&) = delete;
  GraphAtomic& operator=(const GraphAtomic&) = delete;
  int location() const noexcept { return location_; }

 private:
  int location_;
};

template <class T>
class GraphCell {
 public:
  GraphCell() : location_(runtime::new_location(encode(T{}), true)) {}
  GraphCell(const GraphCell&) = delete;
  GraphCell& operator=(const GraphCell&) = delete;
  int location() const noexcept { return location_; }

 private:
  int location_;
};

struct GraphBackend {
  static constexpr std::string_view kName = "graph";

  template <class T>
  using Atomic = GraphAtomic<T>;
  template <class T>
  using Cell = GraphCell<T>;
  using Where = SourceLocation;

  static Access at(Mo mo, Site site, const Where& w) { return {false, mo, true, site, w.file_name(), w.line()}; }

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site site, Where w) {
    return decode<T>(runtime::load(a.location(), at(mo, site, w)));
  }
  template <class T>
  static void store(Atomic<T>& a, T v, Mo mo, Site site, Where w) {
    runtime::store(a.location(), encode(v), at(mo, site, w));
  }
  template <class T>
  static T exchange(Atomic<T>& a, T v, Mo mo, Site site, Where w) {
    const auto update = [&](Value) -> std::optional<Value> { return encode(v); };
    return decode<T>(runtime::read_modify_write(a.location(), ax::Op::exchange, update, at(mo, site, w)));
  }
  template <class T>
  static T fetch_add(Atomic<T>& a, T v, Mo mo, Site site, Where w) {
    const auto update = [&](Value old) -> std::optional<Value> { return encode(static_cast<T>(decode<T>(old) + v)); };
    return decode<T>(runtime::read_modify_write(a.location(), ax::Op::fetch_add, update, at(mo, site, w)));
  }
  template <class T>
  static T fetch_sub(Atomic<T>& a, T v, Mo mo, Site site, Where w) {
    const auto update = [&](Value old) -> std::optional<Value> { return encode(static_cast<T>(decode<T>(old) - v)); };
    return decode<T>(runtime::read_modify_write(a.location(), ax::Op::fetch_add, update, at(mo, site, w)));
  }
  // Strong compare-exchange. A failure is a read alone, with the failure order (the protocol passes relaxed).
  template <class T>
  static bool compare_exchange(Atomic<T>& a, T& expected, T desired, Mo mo, Mo failure, Site site, Where w) {
    const T want = expected;
    bool won = false;
    const auto update = [&](Value old) -> std::optional<Value> {
      won = decode<T>(old) == want;
      if (!won) return std::nullopt;
      return encode(desired);
    };
    (void)failure;  // the read's order is the success order; a failed CAS orders no more than its read does
    const T seen = decode<T>(runtime::read_modify_write(a.location(), ax::Op::cas, update, at(mo, site, w)));
    if (!won) expected = seen;
    return won;
  }

  static void fence(Fence f, Site site, Where w) {
    const Access a = at(Mo::kSeqCst, site, w);
    switch (f) {
      case Fence::kNone:
      case Fence::kCompiler: return;
      case Fence::kAcquire: runtime::fence(ax::Order::acquire, a); return;
      case Fence::kRelease: runtime::fence(ax::Order::release, a); return;
      case Fence::kAcqRel: runtime::fence(ax::Order::acq_rel, a); return;
      case Fence::kSeqCst:
      case Fence::kAsymmetricLight:
      case Fence::kAsymmetricHeavy: runtime::fence(ax::Order::seq_cst, a); return;
    }
  }

  template <class T>
  static T read(const Cell<T>& c, Where w) {
    return decode<T>(
        runtime::load(c.location(), {true, Mo::kRelaxed, false, Site::kOwnerAnnounce, w.file_name(), w.line()}));
  }
  template <class T>
  static void write(Cell<T>& c, T v, Where w) {
    runtime::store(c.location(), encode(v), {true, Mo::kRelaxed, false, Site::kOwnerAnnounce, w.file_name(), w.line()});
  }

  static void invariant(bool holds, const char* what, Where w = Where::current()) {
    if (holds) return;
    const bool lost = std::string_view(what).find("lost") != std::string_view::npos;
    runtime::fail(lost ? Verdict::kLost : Verdict::kOtherFailure, what, w.file_name(), w.line());
  }

  // A wait's iteration failed: spin-assume blocks the thread here (explorer.hpp, WAITS).
  static void spin_pause(Site site, std::uint32_t) { runtime::wait_failed(site); }

  template <class T>
  static void wait_while_equal(const Atomic<T>& a, T old, Mo mo, Site site, Where w) {
    if (load(a, mo, site, w) == old) runtime::wait_failed(site);
  }
  template <class T>
  static void notify_all(Atomic<T>&) noexcept {}
};

}  // namespace frontsteal::graph
