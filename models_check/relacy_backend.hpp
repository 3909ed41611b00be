// relacy_backend.hpp — the atomics backend that runs the protocol inside the Relacy model checker.
//
// Relacy explores thread interleavings and weak-memory reorderings of the *same* protocol source: the
// protocol calls Backend::load/store/... with the site's order and the caller's std::source_location, and
// this backend turns them into rl::atomic operations tagged with an rl::debug_info naming the protocol's own
// file and line, so failure histories point into core/, not here.
//
// Include order matters: relacy.hpp #defines memory_order_*, new, delete, assert and more. Every standard
// and project header is included above it; nothing after it spells those names.
// Modelling choices:
//   - plain shared cells (list bodies, payloads) are rl::var: unordered concurrent access is a data race;
//   - Fence::kCompiler is a no-op (Relacy never reorders a thread's own program order);
//   - the asymmetric pair (light on the owner, membarrier on the thief) is modelled as seq_cst fences on both
//     sides, which is the guarantee membarrier(PRIVATE_EXPEDITED) gives the pair;
//   - spin-waits yield, so Relacy treats them as waiting rather than reporting a livelock.
// Relacy's bounds: each atomic keeps its last few stores and loads never read from the future (no load
// buffering), so a pass is a bounded search, not a proof.
#pragma once

#include <cstdint>
#include <ostream>
#include <source_location>
#include <string_view>

#include "core/memory_order.hpp"
#include "core/site.hpp"

#include <relacy/relacy.hpp>  // last: see above

namespace frontsteal::model {

// rl::var<T> needs T assignable from 0 and printable (for histories): box structured cell values.
template <class T>
struct Boxed {
  T value{};
  Boxed() = default;
  Boxed(T v) : value(v) {}  // NOLINT: implicit on purpose, like the cell it stands for
  Boxed& operator=(int) {
    value = T{};
    return *this;
  }
  friend std::ostream& operator<<(std::ostream& out, const Boxed& b) { return out << b.value; }
};

struct RelacyBackend {
  static constexpr std::string_view kName = "relacy";

  template <class T>
  using Atomic = rl::atomic<T>;
  template <class T>
  using Cell = rl::var<Boxed<T>>;
  using Where = std::source_location;

  static rl::debug_info info(const Where& w) noexcept {
    return rl::debug_info(w.function_name(), w.file_name(), w.line());
  }

  static rl::memory_order native(Mo mo) noexcept {
    switch (mo) {
      case Mo::kRelaxed: return rl::mo_relaxed;
      case Mo::kAcquire: return rl::mo_acquire;
      case Mo::kRelease: return rl::mo_release;
      case Mo::kAcqRel: return rl::mo_acq_rel;
      case Mo::kSeqCst: return rl::mo_seq_cst;
    }
    return rl::mo_seq_cst;
  }

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site, Where w) {
    return a.load(native(mo), info(w));
  }
  template <class T>
  static void store(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    a.store(v, native(mo), info(w));
  }
  template <class T>
  static T exchange(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    return a.exchange(v, native(mo), info(w));
  }
  template <class T>
  static T fetch_add(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    return a.fetch_add(v, native(mo), info(w));
  }
  template <class T>
  static T fetch_sub(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    return a.fetch_sub(v, native(mo), info(w));
  }

  static void fence(Fence f, Site, Where w) {
    switch (f) {
      case Fence::kNone:
      case Fence::kCompiler: return;
      case Fence::kAcquire: rl::atomic_thread_fence(rl::mo_acquire, info(w)); return;
      case Fence::kRelease: rl::atomic_thread_fence(rl::mo_release, info(w)); return;
      case Fence::kAcqRel: rl::atomic_thread_fence(rl::mo_acq_rel, info(w)); return;
      case Fence::kSeqCst:
      case Fence::kAsymmetricLight:
      case Fence::kAsymmetricHeavy: rl::atomic_thread_fence(rl::mo_seq_cst, info(w)); return;
    }
  }

  template <class T>
  static T read(const Cell<T>& c, Where w) {
    return c(info(w)).load().value;
  }
  template <class T>
  static void write(Cell<T>& c, T v, Where w) {
    c(info(w)).store(Boxed<T>(v));
  }

  static void spin_pause(Site, std::uint32_t) { rl::yield(1, rl::debug_info("spin_pause", __FILE__, __LINE__)); }

  template <class T>
  static void wait_while_equal(const Atomic<T>& a, T old, Mo mo, Site, Where w) {
    while (a.load(native(mo), info(w)) == old) rl::yield(1, info(w));
  }
  template <class T>
  static void notify_all(Atomic<T>&) noexcept {}

  static void invariant(bool holds, const char* what, Where w = Where::current()) {
    if (!holds) rl::ctx().fail_test(what, rl::test_result_user_assert_failed, info(w));
  }
};

}  // namespace frontsteal::model
