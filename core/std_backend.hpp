// std_backend.hpp — the production atomics backend: std::atomic, plain cells, native fences.
//
// A backend bundles what differs between the real machine, ThreadSanitizer (stress/) and Relacy
// (models_check/): the atomic template, the plain shared cell (Relacy must see races on it), fences, the
// spin-wait hint, and blocking waits. Every operation takes the Site it serves and the caller's source
// location, so other backends can inject chaos there or name the protocol's own line in a trace; this one
// ignores both and compiles to the bare instruction.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>
#include <thread>

#include "core/check.hpp"
#include "core/membarrier.hpp"
#include "core/memory_order.hpp"
#include "core/site.hpp"
#include "core/source_location.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace frontsteal {

// A plain (non-atomic) shared variable. Access goes through the backend so Relacy can check it for races.
template <class T>
struct PlainCell {
  T value{};
};

struct StdBackend {
  static constexpr std::string_view kName = "std";

  template <class T>
  using Atomic = std::atomic<T>;
  template <class T>
  using Cell = PlainCell<T>;
  using Where = SourceLocation;

  static constexpr std::memory_order native(Mo mo) noexcept {
    switch (mo) {
      case Mo::kRelaxed: return std::memory_order::relaxed;
      case Mo::kAcquire: return std::memory_order::acquire;
      case Mo::kRelease: return std::memory_order::release;
      case Mo::kAcqRel: return std::memory_order::acq_rel;
      case Mo::kSeqCst: return std::memory_order::seq_cst;
    }
    return std::memory_order::seq_cst;
  }

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site, Where) noexcept {
    return a.load(native(mo));
  }
  template <class T>
  static void store(Atomic<T>& a, T v, Mo mo, Site, Where) noexcept {
    a.store(v, native(mo));
  }
  template <class T>
  static T exchange(Atomic<T>& a, T v, Mo mo, Site, Where) noexcept {
    return a.exchange(v, native(mo));
  }
  template <class T>
  static T fetch_add(Atomic<T>& a, T v, Mo mo, Site, Where) noexcept {
    return a.fetch_add(v, native(mo));
  }
  template <class T>
  static T fetch_sub(Atomic<T>& a, T v, Mo mo, Site, Where) noexcept {
    return a.fetch_sub(v, native(mo));
  }
  template <class T>
  static bool compare_exchange(Atomic<T>& a, T& expected, T desired, Mo mo, Mo failure, Site, Where) noexcept {
    return a.compare_exchange_strong(expected, desired, native(mo), native(failure));
  }

  static void fence(Fence f, Site, Where) noexcept {
    switch (f) {
      case Fence::kNone: return;
      case Fence::kCompiler:
      case Fence::kAsymmetricLight: std::atomic_signal_fence(std::memory_order::seq_cst); return;
      case Fence::kAcquire: std::atomic_thread_fence(std::memory_order::acquire); return;
      case Fence::kRelease: std::atomic_thread_fence(std::memory_order::release); return;
      case Fence::kAcqRel: std::atomic_thread_fence(std::memory_order::acq_rel); return;
      case Fence::kSeqCst: std::atomic_thread_fence(std::memory_order::seq_cst); return;
      case Fence::kAsymmetricHeavy: membarrier_heavy_fence(); return;
    }
  }

  template <class T>
  static T read(const Cell<T>& c, Where) noexcept {
    return c.value;
  }

  // A diagnostic read (a watchdog's snapshot), not a protocol site: relaxed, so it orders nothing and adds no
  // fence; atomic, so ThreadSanitizer sees no race. Derived backends inherit it unchanged: a snapshot must not
  // inject chaos or otherwise perturb the run it describes. Backends whose threads are not std::threads
  // (Relacy) do not provide it; nothing in the protocol calls it.
  template <class T>
  static T peek(const Atomic<T>& a) noexcept {
    return a.load(std::memory_order::relaxed);
  }
  template <class T>
  static void write(Cell<T>& c, T v, Where) noexcept {
    c.value = v;
  }

  // A protocol invariant (programmer error, never bad input): abort with the message and location.
  static void invariant(bool holds, const char* what, Where where = Where::current()) noexcept {
    if (!holds) detail::check_failed(what, std::string(), where.file_name(), static_cast<int>(where.line()));
  }

  // One iteration of a busy-wait (the thief on ListTransient, an idle worker looking for work, an owner
  // taking its own lock). `spins` counts this wait's iterations: after a short burst of pause instructions
  // the thread yields its core, because with more workers than cores the thread it waits for may be the
  // one that is not running (paper §4.2.2 footnote 2 assumes one processor per worker).
  static void spin_pause(Site, std::uint32_t spins) noexcept {
    if (spins < kSpinsBeforeYield) {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }
  static constexpr std::uint32_t kSpinsBeforeYield = 64;

  // Blocks while `a` holds `old` (frame boundaries only; never on the protocol's hot paths). Spins briefly
  // first because the next frame usually starts within microseconds, then sleeps in the kernel (futex).
  template <class T>
  static void wait_while_equal(const Atomic<T>& a, T old, Mo mo, Site, Where) noexcept {
    for (int i = 0; i < 2048; ++i) {
      if (a.load(native(mo)) != old) return;
      spin_pause(Site::kFrameAwaitStart, 0);
    }
    while (a.load(native(mo)) == old) a.wait(old, native(mo));
  }
  template <class T>
  static void notify_all(Atomic<T>& a) noexcept {
    a.notify_all();
  }
};

}  // namespace frontsteal
