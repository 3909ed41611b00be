// spsc_ring.hpp — a user's own lock-free structure: a bounded single-producer single-consumer ring.
//
// Written once against a frontsteal backend (core/std_backend.hpp): every shared access goes through
// Backend::load/store (atomics, with the order its Orders class gives) or Backend::read/write (the plain slot
// cells), so the same source runs on std::atomic (StdBackend) and inside the Relacy model checker
// (frontsteal::model::RelacyBackend), where a plain cell read without happens-before from its write is a
// data race.
//
// ORDERS
//   R1  producer: tail := t + 1    release — publishes the slot written just before (W)
//   R2  consumer: read tail        acquire — pairs with R1: the slot's write happens before its read
//   R3  consumer: head := h + 1    release — the slot's read happens before the producer reuses it
//   R4  producer: read head        acquire — pairs with R3
// The own index of each side is read relaxed (only that side writes it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <source_location>

#include "core/memory_order.hpp"
#include "core/site.hpp"

namespace user {

// The sound orders, and the only knob a mutant turns.
struct SoundOrders {
  static constexpr const char* kName = "sound (release/acquire)";
  static constexpr frontsteal::Mo kPublishTail = frontsteal::Mo::kRelease;  // R1
  static constexpr frontsteal::Mo kReadTail = frontsteal::Mo::kAcquire;     // R2
  static constexpr frontsteal::Mo kReleaseHead = frontsteal::Mo::kRelease;  // R3
  static constexpr frontsteal::Mo kReadHead = frontsteal::Mo::kAcquire;     // R4
};

template <class T, std::uint32_t Capacity, class Backend, class Orders = SoundOrders>
class SpscRing {
  template <class U>
  using Atomic = typename Backend::template Atomic<U>;
  using Where = typename Backend::Where;
  // frontsteal's backends take the protocol site of every access (for chaos injection and traces of
  // frontsteal's own protocols). This structure is not one of them: it passes the end marker, which the std
  // and Relacy backends ignore.
  static constexpr frontsteal::Site kSite = frontsteal::Site::kCount;
  static constexpr frontsteal::Mo kOwn = frontsteal::Mo::kRelaxed;

 public:
  // Producer only. False when full.
  bool try_push(T v) {
    const std::uint32_t t = Backend::load(tail_, kOwn, kSite, Where::current());
    const std::uint32_t h = Backend::load(head_, Orders::kReadHead, kSite, Where::current());  // R4
    if (t - h == Capacity) return false;
    Backend::write(slots_[t % Capacity], v, Where::current());                    // W
    Backend::store(tail_, t + 1, Orders::kPublishTail, kSite, Where::current());  // R1
    return true;
  }
  // Consumer only. False when empty.
  bool try_pop(T& out) {
    const std::uint32_t h = Backend::load(head_, kOwn, kSite, Where::current());
    const std::uint32_t t = Backend::load(tail_, Orders::kReadTail, kSite, Where::current());  // R2
    if (h == t) return false;
    out = Backend::read(slots_[h % Capacity], Where::current());
    Backend::store(head_, h + 1, Orders::kReleaseHead, kSite, Where::current());  // R3
    return true;
  }

 private:
  Atomic<std::uint32_t> head_{0};  // next slot to read; written by the consumer
  Atomic<std::uint32_t> tail_{0};  // next slot to write; written by the producer
  typename Backend::template Cell<T> slots_[Capacity];
};

}  // namespace user
