// memory_order.hpp — the protocol's own names for memory orders and fences.
//
// Protocol files never spell std::memory_order_x: Relacy #defines those names, and a policy must be able to
// name an order the same way for every backend. Each backend maps Mo and Fence to its native form.
#pragma once

#include <cstdint>
#include <string_view>

namespace frontsteal {

// Memory order of one atomic access, weakest first: weakening a site moves it one step to the left.
enum class Mo : std::uint8_t { kRelaxed, kAcquire, kRelease, kAcqRel, kSeqCst };

// What a fence site does. kAsymmetricLight/Heavy are the two halves of an asymmetric fence: the light side
// only stops the compiler; the heavy side (membarrier) makes every other thread's light side a full fence.
enum class Fence : std::uint8_t {
  kNone,
  kCompiler,
  kAcquire,
  kRelease,
  kAcqRel,
  kSeqCst,
  kAsymmetricLight,
  kAsymmetricHeavy
};

constexpr std::string_view name(Mo mo) noexcept {
  switch (mo) {
    case Mo::kRelaxed: return "relaxed";
    case Mo::kAcquire: return "acquire";
    case Mo::kRelease: return "release";
    case Mo::kAcqRel: return "acq_rel";
    case Mo::kSeqCst: return "seq_cst";
  }
  return "?";
}

constexpr std::string_view name(Fence f) noexcept {
  switch (f) {
    case Fence::kNone: return "none";
    case Fence::kCompiler: return "compiler";
    case Fence::kAcquire: return "acquire";
    case Fence::kRelease: return "release";
    case Fence::kAcqRel: return "acq_rel";
    case Fence::kSeqCst: return "seq_cst";
    case Fence::kAsymmetricLight: return "asymmetric_light";
    case Fence::kAsymmetricHeavy: return "asymmetric_heavy(membarrier)";
  }
  return "?";
}

// A fence that orders an earlier store before a later load of the same thread (StoreLoad), either by itself
// (seq_cst) or together with the other side's heavy fence (asymmetric light).
constexpr bool orders_store_load(Fence f) noexcept { return f == Fence::kSeqCst || f == Fence::kAsymmetricHeavy; }

}  // namespace frontsteal
