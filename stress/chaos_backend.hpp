// chaos_backend.hpp — the stress backend: std atomics, chaos injected at labelled sites, fences made visible
// to ThreadSanitizer.
//
// Chaos. At every labelled access the calling thread may, with a configurable probability, yield, spin a
// few hundred cycles or sleep a few microseconds, widening the race windows the handshake must close (the
// owner between O2 and O3, a thief between T1 and T3, ...). Decisions come from a per-thread xorshift
// generator seeded from (run seed, thread number), so a run is reproducible up to the OS scheduler.
//
// Fences under ThreadSanitizer. GCC 12's TSan does not model std::atomic_thread_fence (-Wtsan says so) and
// knows nothing of membarrier, so a correct fence-based synchronization would be reported as a race. Under
// __SANITIZE_THREAD__ every fence also releases and acquires one global token (__tsan_release/__tsan_acquire):
// TSan then sees a happens-before edge from every fence to every later fence. That is an over-approximation
// (it can hide a race that only a missing fence allows; the model checker and the release-build duplicate
// rates cover that case), chosen so that TSan reports only races that no fence ordering could excuse.
// Outside TSan the annotations vanish and fences are the std backend's.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <thread>

#include "core/std_backend.hpp"

#if defined(__SANITIZE_THREAD__)
#include <sanitizer/tsan_interface.h>
#endif

namespace frontsteal::stress {

// Process-wide chaos settings; set before a run starts, read-only during it.
struct ChaosSettings {
  std::uint32_t per_million = 0;  // probability of an injection at each labelled access, per million
  std::uint64_t seed = 1;
};

inline ChaosSettings& chaos_settings() {
  static ChaosSettings s;
  return s;
}

inline std::atomic<std::uint64_t>& chaos_injections() {
  static std::atomic<std::uint64_t> n{0};
  return n;
}

namespace detail {
inline std::atomic<std::uint32_t> next_thread_number{0};

#if defined(__SANITIZE_THREAD__)
inline char fence_token;
#endif

inline std::uint64_t next_random() noexcept {
  thread_local std::uint64_t state = [] {
    std::uint64_t s = chaos_settings().seed * 0x9E3779B97F4A7C15ull + next_thread_number.fetch_add(1) + 1;
    return s == 0 ? 1 : s;
  }();
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return state;
}

inline void maybe_inject() noexcept {
  const std::uint32_t rate = chaos_settings().per_million;
  if (rate == 0) return;
  const std::uint64_t r = next_random();
  if (r % 1000000 >= rate) return;
  chaos_injections().fetch_add(1, std::memory_order::relaxed);
  switch ((r >> 32) % 3) {
    case 0: std::this_thread::yield(); break;
    case 1:
      for (int i = 0; i < 200; ++i) StdBackend::spin_pause(Site::kCount, 0);
      break;
    default: std::this_thread::sleep_for(std::chrono::microseconds(5)); break;
  }
}
}  // namespace detail

struct ChaosBackend : StdBackend {
  static constexpr std::string_view kName = "chaos";

  template <class T>
  static T load(const Atomic<T>& a, Mo mo, Site site, Where where) noexcept {
    detail::maybe_inject();
    return StdBackend::load(a, mo, site, where);
  }
  template <class T>
  static void store(Atomic<T>& a, T v, Mo mo, Site site, Where where) noexcept {
    detail::maybe_inject();
    StdBackend::store(a, v, mo, site, where);
  }
  template <class T>
  static T exchange(Atomic<T>& a, T v, Mo mo, Site site, Where where) noexcept {
    detail::maybe_inject();
    return StdBackend::exchange(a, v, mo, site, where);
  }
  template <class T>
  static T fetch_add(Atomic<T>& a, T v, Mo mo, Site site, Where where) noexcept {
    detail::maybe_inject();
    return StdBackend::fetch_add(a, v, mo, site, where);
  }
  template <class T>
  static T fetch_sub(Atomic<T>& a, T v, Mo mo, Site site, Where where) noexcept {
    detail::maybe_inject();
    return StdBackend::fetch_sub(a, v, mo, site, where);
  }
  template <class T>
  static bool compare_exchange(Atomic<T>& a, T& expected, T desired, Mo mo, Mo failure, Site site,
                               Where where) noexcept {
    detail::maybe_inject();
    return StdBackend::compare_exchange(a, expected, desired, mo, failure, site, where);
  }
  static void fence(Fence f, Site site, Where where) noexcept {
    detail::maybe_inject();
#if defined(__SANITIZE_THREAD__)
    if (f != Fence::kNone && f != Fence::kCompiler) {  // the asymmetric light side counts: membarrier orders it
      __tsan_acquire(&detail::fence_token);
      __tsan_release(&detail::fence_token);
    }
#endif
    StdBackend::fence(f, site, where);
  }
};

}  // namespace frontsteal::stress
