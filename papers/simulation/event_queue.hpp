// event_queue.hpp — the clock of every discrete-event model (papers/simulator.cpp for shared memory,
// distributed/rma_simulator.cpp for MPI ranks): events (time, worker) handed out in time order.
//
// A model's shared state changes only at event instants; between two events of a worker it only runs items.
// Equal times are broken deterministically, so a model with a fixed seed replays the same run:
//   Ties::kByWorker        the lower worker first (the shared-memory models: workers woken together start in
//                          id order, as notify_all wakes them).
//   Ties::kInArrivalOrder  the event scheduled first goes first (the distributed model: a round trip's reply
//                          and a rank's next step at one instant keep the order the model issued them in).
// A model that keeps scheduling events without end (a livelock of the model, not of the protocol) stops at the
// event limit with an exception instead of running forever.
#pragma once

#include <cstdint>
#include <functional>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace frontsteal::simulation {

enum class Ties : std::uint8_t { kByWorker, kInArrivalOrder };

template <typename Worker>
class EventQueue {
 public:
  struct Event {
    double at;
    Worker worker;
  };

  explicit EventQueue(Ties ties, std::uint64_t event_limit = 2'000'000'000ull) : ties_(ties), limit_(event_limit) {}

  void push(double at, Worker worker) {
    const std::uint64_t key = ties_ == Ties::kByWorker ? static_cast<std::uint64_t>(worker) : arrivals_++;
    heap_.emplace(at, key, worker);
  }
  bool empty() const noexcept { return heap_.empty(); }
  // The earliest event, removed. Throws std::runtime_error past the event limit.
  Event pop() {
    if (++popped_ > limit_) throw std::runtime_error("simulator: event limit reached (a livelock in the model)");
    const auto [at, key, worker] = heap_.top();
    heap_.pop();
    return {at, worker};
  }
  std::uint64_t events_handled() const noexcept { return popped_; }

 private:
  using Entry = std::tuple<double, std::uint64_t, Worker>;
  Ties ties_;
  std::uint64_t limit_;
  std::uint64_t arrivals_ = 0, popped_ = 0;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap_;
};

}  // namespace frontsteal::simulation
