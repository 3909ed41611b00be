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
//   - spin-waits yield, so Relacy treats them as waiting rather than reporting a livelock;
//   - in tree searches (context-bound, full) every wait is bounded ("spin-assume", below), which makes each
//     scenario a finite program, so those searches finish.
//
// SPIN BOUND ("spin-assume", as stateless model checkers such as GenMC treat await loops)
//   Every wait and poll of the protocol reaches this backend through one of two hooks: spin_pause(site, n)
//   after the n+1-th failed iteration of a loop (T4 await ListTransient, A3 idle-round poll, L1/L2 owner's
//   lock_spinning; D1, the publication driver's wait for the pusher), and wait_while_equal (E2/E6 frame
//   waits); the publication harness's own frame waits call failed_iteration directly (publication_suite.cpp). With
//   SpinBound::k = K > 0 a loop may fail K times; the execution in which it would fail a K+1-th time is DISCARDED: the
//   thread leaves its body at once (longjmp to the suite's thread(), which set the landing point: ProtocolSuite,
//   PublicationSuite, ChaseLevSuite), every other thread leaves at its next backend call, and the harness skips the
//   end-of-execution checks and counts the execution as discarded. A discarded execution's prefix is still a real
//   execution prefix: a failure Relacy reports in it (a duplicate, a data race) is real. Why no bug class is lost: a
//   failed iteration only reads (T4, E2, E6, A3) or takes and releases a lock it found free, and restores every value
//   it wrote (L1-L3 around an empty or busy victim); its reads see no new value, so it is invisible to every other
//   thread. An execution in which a loop fails more often than K therefore has the same reads-from relation on its
//   effectful events as the execution in which the other threads' steps between the redundant iterations ran first and
//   the loop failed at most K times, and the checker explores that one. What the bound gives up is liveness: a thread
//   that would wait forever is discarded, not reported, so the tree searches check safety only. The random search runs
//   the unbounded program (SpinBound off) and still reports a livelock when an execution exceeds Relacy's
//   depth limit; every tree search must also complete at least one execution, or the cell fails as vacuous.
//   One caveat with an idle round: a round whose steal came out empty after lowering a victim's End
//   (kSkippedAll) did change End, but only to a value at or below the victim's Front, so every later round
//   sees that victim empty, as it would have without the extra round.
//   Longjmp skips no destructor that matters: between ProtocolSuite::thread and a backend call the frames of
//   the frame loop and the protocol hold only trivially destructible locals (ids, counters, spans).
// Relacy's bounds: each atomic keeps its last few stores and loads never read from the future (no load
// buffering), so a pass is a bounded search, not a proof.
#pragma once

#include <csetjmp>
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

// The spin bound's state: one per process. Relacy runs every thread of an execution on fibers of one OS
// thread, so plain globals are coherent with the interleaving; every suite's before() re-arms it.
struct SpinBound {
  static constexpr unsigned kMaxThreads = 8;
  unsigned k = 0;                   // failed iterations allowed per wait; 0: unbounded (random search)
  bool discarded = false;           // this execution exceeded the bound somewhere
  std::jmp_buf exits[kMaxThreads];  // landing point of each thread body (set by ProtocolSuite::thread)

  // Leaves the current thread's body: the execution is discarded.
  [[noreturn]] void leave() {
    discarded = true;
    std::longjmp(exits[rl::thread_index()], 1);
  }
  // Called at every backend operation: once discarded, threads stop at their next step.
  void stop_if_discarded() {
    if (discarded) leave();
  }
  // Called after the `failures`-th failed iteration of one wait. Frame waits (E2/E6) get one more: a thread
  // that waits for a whole frame is offered the processor at every forced switch of the frame (each other
  // thread's own wait), so with k = 1 the context-bound scheduler found no complete execution of
  // caller_handoff at all (every one discarded: a vacuous search).
  void failed_iteration(std::uint32_t failures, bool frame_wait = false) {
    if (k != 0 && failures > k + (frame_wait ? 1u : 0u)) leave();
  }
};

inline SpinBound& spin_bound() {
  static SpinBound b;
  return b;
}

// Termination check (harness): called when a worker's A3 poll reads an active count of 0, i.e. when the
// worker is about to stop looking for work. The harness checks that every item of its frame has run.
inline void (*idle_seen_hook)() = nullptr;

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
  static T load(const Atomic<T>& a, Mo mo, Site site, Where w) {
    spin_bound().stop_if_discarded();
    const T v = a.load(native(mo), info(w));
    if (site == Site::kActivePoll && v == T{} && idle_seen_hook != nullptr) idle_seen_hook();
    return v;
  }
  template <class T>
  static void store(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    spin_bound().stop_if_discarded();
    a.store(v, native(mo), info(w));
  }
  template <class T>
  static T exchange(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    spin_bound().stop_if_discarded();
    return a.exchange(v, native(mo), info(w));
  }
  template <class T>
  static T fetch_add(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    spin_bound().stop_if_discarded();
    return a.fetch_add(v, native(mo), info(w));
  }
  template <class T>
  static T fetch_sub(Atomic<T>& a, T v, Mo mo, Site, Where w) {
    spin_bound().stop_if_discarded();
    return a.fetch_sub(v, native(mo), info(w));
  }
  template <class T>
  static bool compare_exchange(Atomic<T>& a, T& expected, T desired, Mo mo, Mo failure, Site, Where w) {
    spin_bound().stop_if_discarded();
    return a.compare_exchange_strong(expected, desired, native(mo), info(w), native(failure), info(w));
  }

  static void fence(Fence f, Site, Where w) {
    spin_bound().stop_if_discarded();
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

  // `spins` failed iterations preceded this one (the protocol's loops count from 0).
  static void spin_pause(Site, std::uint32_t spins) {
    spin_bound().failed_iteration(spins + 1);
    rl::yield(1, rl::debug_info("spin_pause", __FILE__, __LINE__));
  }

  template <class T>
  static void wait_while_equal(const Atomic<T>& a, T old, Mo mo, Site site, Where w) {
    for (std::uint32_t failures = 1;; ++failures) {
      spin_bound().stop_if_discarded();
      if (a.load(native(mo), info(w)) != old) return;
      spin_bound().failed_iteration(failures, site == Site::kFrameAwaitStart || site == Site::kFrameAwaitDone);
      rl::yield(1, info(w));
    }
  }
  template <class T>
  static void notify_all(Atomic<T>&) noexcept {}

  static void invariant(bool holds, const char* what, Where w = Where::current()) {
    if (!holds) rl::ctx().fail_test(what, rl::test_result_user_assert_failed, info(w));
  }
};

}  // namespace frontsteal::model
