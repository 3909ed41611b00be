// The Chase–Lev deque (core/chase_lev_deque.hpp, as the scheduler uses it through schedulers/chase_lev_deque.hpp):
// sequential semantics, capacity, and every element taken exactly once when an owner races thieves, on std atomics
// and under the stress backend's chaos injection.
#include <atomic>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "core/execution_counter.hpp"
#include "schedulers/chase_lev_deque.hpp"
#include "stress/chaos_backend.hpp"

namespace sc = frontsteal::sched;

TEST_CASE("owner takes LIFO, thieves steal FIFO, a full deque refuses a push", "[chase-lev]") {
  sc::ChaseLevDeque<std::uint64_t> d(4);
  std::uint64_t x = 0;
  REQUIRE_FALSE(d.take(x));
  REQUIRE(d.steal(x) == sc::StealResult::kEmpty);
  for (std::uint64_t i = 1; i <= 4; ++i) REQUIRE(d.push(i));
  REQUIRE_FALSE(d.push(5));
  REQUIRE(d.steal(x) == sc::StealResult::kSuccess);
  REQUIRE(x == 1);
  REQUIRE(d.take(x));
  REQUIRE(x == 4);
  REQUIRE(d.push(6));  // room again, wrapping the ring
  REQUIRE(d.take(x));
  REQUIRE(x == 6);
  REQUIRE(d.take(x));
  REQUIRE(x == 3);
  REQUIRE(d.take(x));
  REQUIRE(x == 2);
  REQUIRE_FALSE(d.take(x));
  REQUIRE(d.size_hint() == 0);
}

namespace {

template <class Deque>
void owner_races_three_thieves(std::uint32_t kElements) {
  Deque d(64);
  frontsteal::ExecutionCounter taken(kElements);
  std::atomic<bool> done{false};
  std::vector<std::thread> thieves;
  for (int t = 0; t < 3; ++t) {
    thieves.emplace_back([&] {
      std::uint64_t x;
      while (!done.load(std::memory_order::acquire)) {
        if (d.steal(x) == sc::StealResult::kSuccess) taken.record(static_cast<std::uint32_t>(x));
      }
    });
  }
  std::uint32_t next = 0;
  std::uint64_t x;
  while (next < kElements) {
    // Push a few, take one: the deque stays short, so the last-element race (T5 against S5) is frequent.
    for (int k = 0; k < 3 && next < kElements; ++k) {
      while (!d.push(next)) {
        if (d.take(x)) taken.record(static_cast<std::uint32_t>(x));
      }
      ++next;
    }
    if (d.take(x)) taken.record(static_cast<std::uint32_t>(x));
  }
  while (d.take(x)) taken.record(static_cast<std::uint32_t>(x));
  while (d.size_hint() > 0) std::this_thread::yield();  // thieves finish what they saw
  done.store(true, std::memory_order::release);
  for (auto& t : thieves) t.join();
  const auto a = taken.audit_and_reset();
  INFO(a);
  REQUIRE(a.exactly_once());
}

}  // namespace

TEST_CASE("an owner racing three thieves: every element is taken exactly once", "[chase-lev]") {
  owner_races_three_thieves<sc::ChaseLevDeque<std::uint64_t>>(200000);
}

TEST_CASE("the same race under chaos injection at every labelled site", "[chase-lev]") {
  namespace st = frontsteal::stress;
  const st::ChaosSettings saved = st::chaos_settings();
  st::chaos_settings().per_million = 20000;  // 2 % of the deque's accesses yield, spin or sleep
  st::chaos_settings().seed = 7;
  const std::uint64_t before = st::chaos_injections().load();
  owner_races_three_thieves<frontsteal::ChaseLevDeque<std::uint64_t, st::ChaosBackend, frontsteal::ChaseLevOrders>>(
      20000);
  st::chaos_settings() = saved;
  REQUIRE(st::chaos_injections().load() > before);  // the chaos did happen
}
