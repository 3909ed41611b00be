// distributed/refill_budget.hpp: the rule a hier refill takes items by. Known costs fill the target and are not
// capped; an unknown item is priced by the worker's last item (the whole target before its first: one item);
// unknown items are capped at twice the last refill and at a (2 x threads)-th of the rank list's unclaimed items.
#include <catch2/catch.hpp>

#include <cstdint>

#include "distributed/refill_budget.hpp"

namespace mpi = frontsteal::mpi;

namespace {

// How many items a budget admits out of `offered` items that all cost `known_ns` (negative: unknown).
std::uint32_t admitted(mpi::RefillBudget b, double known_ns, std::uint32_t offered = 100000) {
  std::uint32_t n = 0;
  while (n < offered && b.admit(known_ns)) ++n;
  return n;
}

}  // namespace

TEST_CASE("a refill of known items fills the target, the item that reaches it included", "[distributed][refill]") {
  const mpi::RefillHistory fresh;
  CHECK(admitted(mpi::RefillBudget(50'000, 256, fresh, 100000, 16), 10'000) == 5);
  CHECK(admitted(mpi::RefillBudget(50'000, 256, fresh, 100000, 16), 12'000) == 5);   // 48 us, then one more
  CHECK(admitted(mpi::RefillBudget(50'000, 256, fresh, 100000, 16), 200'000) == 1);  // one heavy item
  CHECK(admitted(mpi::RefillBudget(50'000, 256, fresh, 100000, 16), 1) == 256);      // the hard cap
  // Known items are not capped by the unknown items' share: 4 unclaimed among 16 threads still gives 5.
  CHECK(admitted(mpi::RefillBudget(50'000, 256, fresh, 4, 16), 10'000) == 5);
}

TEST_CASE("a refill measures before it commits to unknown items", "[distributed][refill]") {
  // Before the worker's first item of the frame: one unknown item, whatever the target.
  CHECK(admitted(mpi::RefillBudget(50'000, 256, mpi::RefillHistory{}, 100000, 16), -1) == 1);
  // Priced by the worker's last item: 50 us / 10 us = 5 items (the last refill allows up to 2 x 100).
  const mpi::RefillHistory ten_us{10'000, 100};
  CHECK(admitted(mpi::RefillBudget(50'000, 256, ten_us, 100000, 16), -1) == 5);
  // Growth: a last item of 1 us would allow 50, but the last refill took 3: at most 6.
  const mpi::RefillHistory grew{1'000, 3};
  CHECK(admitted(mpi::RefillBudget(50'000, 256, grew, 100000, 16), -1) == 6);
  // Share: 64 unclaimed items among 16 threads: at most 64 / 32 = 2; and never fewer than one.
  const mpi::RefillHistory light{100, 200};
  CHECK(admitted(mpi::RefillBudget(50'000, 256, light, 64, 16), -1) == 2);
  CHECK(admitted(mpi::RefillBudget(50'000, 256, light, 3, 16), -1) == 1);
  CHECK(admitted(mpi::RefillBudget(50'000, 256, light, 3, 0), -1) == 1);  // no threads counts as one
}

TEST_CASE("the unknown items' cap leaves known items after them admissible", "[distributed][refill]") {
  mpi::RefillBudget b(50'000, 256, mpi::RefillHistory{}, 100000, 16);
  CHECK(b.admit(1'000));        // known: 1 us
  CHECK(b.admit(-1));           // the one unknown item allowed, priced at the target: 51 us in all
  CHECK_FALSE(b.admit(1'000));  // the target is reached
  CHECK(b.taken() == 2);
  CHECK(b.worth_ns() == 51'000);
  mpi::RefillBudget c(50'000, 256, mpi::RefillHistory{1'000, 1}, 100000, 16);  // unknown cap 2
  CHECK(c.admit(-1));
  CHECK(c.admit(-1));
  CHECK_FALSE(c.admit(-1));
  CHECK(c.admit(1'000));  // a known item is still admitted after the cap: 3 us so far
  CHECK(c.taken() == 3);
}
