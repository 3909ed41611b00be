// papers/simulation/: the discrete-event core shared by the shared-memory and the MPI models.
#include <catch2/catch.hpp>

#include <random>
#include <stdexcept>
#include <vector>

#include "papers/simulation/event_queue.hpp"
#include "papers/simulation/exactly_once_audit.hpp"
#include "papers/simulation/stealing_lists.hpp"

namespace sim = frontsteal::simulation;
using frontsteal::ItemId;

namespace {
template <typename Queue>
std::vector<int> drain(Queue& q) {
  std::vector<int> order;
  while (!q.empty()) order.push_back(q.pop().worker);
  return order;
}
}  // namespace

TEST_CASE("events come in time order, equal times by worker or by arrival", "[papers][simulation]") {
  sim::EventQueue<int> by_worker(sim::Ties::kByWorker);
  by_worker.push(1.0, 3);
  by_worker.push(1.0, 1);
  by_worker.push(0.5, 2);
  by_worker.push(2.0, 0);
  CHECK(drain(by_worker) == std::vector<int>{2, 1, 3, 0});

  sim::EventQueue<int> by_arrival(sim::Ties::kInArrivalOrder);
  by_arrival.push(1.0, 3);
  by_arrival.push(1.0, 1);
  by_arrival.push(0.5, 2);
  by_arrival.push(1.0, 0);
  CHECK(drain(by_arrival) == std::vector<int>{2, 3, 1, 0});
  CHECK(by_arrival.events_handled() == 4);
}

TEST_CASE("a model that never stops scheduling ends at the event limit", "[papers][simulation]") {
  sim::EventQueue<int> q(sim::Ties::kByWorker, 100);
  q.push(0, 0);
  auto livelock = [&] {
    while (!q.empty()) {
      const auto e = q.pop();
      q.push(e.at + 1, e.worker);  // always one more step
    }
  };
  CHECK_THROWS_AS(livelock(), std::runtime_error);
  CHECK(q.events_handled() == 101);
}

TEST_CASE("the audit passes a partition and names the first lost or duplicated item", "[papers][simulation]") {
  sim::ExactlyOnceAudit audit(5);
  audit.count({0, 1, 4});
  audit.count({3, 2});
  CHECK_FALSE(audit.first_failure().has_value());

  audit.clear();  // planted: item 2 lost, item 4 run twice
  audit.count({0, 1, 4});
  audit.count({3, 4});
  const auto failure = audit.first_failure();
  REQUIRE(failure.has_value());
  CHECK(failure->item == 2);
  CHECK(failure->runs == 0);
  CHECK(failure->what() == "item 2 executed 0 times");

  audit.clear();  // planted: a duplicate only
  audit.count({0, 1, 2, 3, 4});
  audit.count({3});
  REQUIRE(audit.first_failure().has_value());
  CHECK(audit.first_failure()->item == 3);
  CHECK(audit.first_failure()->runs == 2);
}

TEST_CASE("first lists are contiguous blocks covering every item once", "[papers][simulation]") {
  const auto lists = sim::contiguous_blocks(10, 3);
  REQUIRE(lists.size() == 3);
  CHECK(lists[0] == std::vector<ItemId>{0, 1, 2});
  CHECK(lists[1] == std::vector<ItemId>{3, 4, 5});
  CHECK(lists[2] == std::vector<ItemId>{6, 7, 8, 9});
  CHECK(sim::contiguous_blocks(2, 4)[0].empty());  // more workers than items: some start empty
}

TEST_CASE("a victim order visits every other worker once", "[papers][simulation]") {
  std::mt19937_64 rng(7);
  for (unsigned self = 0; self < 6; ++self) {
    auto order = sim::victim_order(self, 6u, rng);
    REQUIRE(order.size() == 5);
    std::sort(order.begin(), order.end());
    for (unsigned i = 0, v = 0; v < 6; ++v) {
      if (v == self) continue;
      CHECK(order[i++] == v);
    }
  }
}

TEST_CASE("a steal takes the upper half, the victim keeps the lower (rounded down)", "[papers][simulation]") {
  CHECK(sim::steal_mid(4u, 9u) == 6u);  // 5 left: victim keeps 2, thief takes [6, 9)
  CHECK(sim::steal_mid(0u, 1u) == 0u);  // 1 left: the thief takes it
  CHECK(sim::steal_mid(10u, 20u) == 15u);
}

TEST_CASE("the next frame's lists are what each worker ran, in id order, duplicates to the first",
          "[papers][simulation]") {
  const std::vector<std::vector<ItemId>> ran{{5, 0, 2}, {1, 2, 4}, {3}};
  const auto next = sim::lists_from_runs(ran, 6);
  CHECK(next[0] == std::vector<ItemId>{0, 2, 5});
  CHECK(next[1] == std::vector<ItemId>{1, 4});
  CHECK(next[2] == std::vector<ItemId>{3});
}
