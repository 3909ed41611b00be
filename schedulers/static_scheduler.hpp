// static_scheduler.hpp — static allocation (paper §3): every worker processes a fixed list of items, chosen
// once before the first frame; no communication during a frame. The lists come from
// static_assignment.hpp (round robin, Morton deal, simulated-annealing partition).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "schedulers/scheduler.hpp"
#include "schedulers/team_scheduler.hpp"

namespace frontsteal::sched {

// Per worker, the items it processes, in order.
using Assignment = std::vector<std::vector<ItemId>>;

// Throws std::invalid_argument unless `a` has `workers` lists that together hold every id in [0, items) once.
inline void require_partition(const Assignment& a, WorkerId workers, ItemId items) {
  if (a.size() != workers) throw std::invalid_argument("frontsteal: assignment has the wrong number of workers");
  std::vector<char> seen(items, 0);
  for (const auto& list : a) {
    for (ItemId id : list) {
      if (id >= items || seen[id]) {
        throw std::invalid_argument("frontsteal: assignment is not a partition of the items (id " + std::to_string(id) +
                                    ")");
      }
      seen[id] = 1;
    }
  }
  for (ItemId id = 0; id < items; ++id) {
    if (!seen[id]) throw std::invalid_argument("frontsteal: assignment misses item " + std::to_string(id));
  }
}

class StaticScheduler final : public TeamScheduler<StaticScheduler> {
 public:
  // The partition is checked before the base starts the team: a bad assignment starts no thread.
  StaticScheduler(const SchedulerConfig& config, Assignment assignment)
      : TeamScheduler((require_partition(assignment, config.workers, config.items), config.workers)),
        assignment_(std::move(assignment)) {}

  const Assignment& assignment() const noexcept { return assignment_; }

 private:
  friend class TeamScheduler<StaticScheduler>;
  void work(WorkerId w) {
    WorkerSlot& me = slot(w);
    const Clock::time_point start = Clock::now();  // one pair of clock reads per frame: always on
    for (ItemId id : assignment_[w]) me.run(process(), id, w);
    me.add_claim(start, Clock::now());
  }

  Assignment assignment_;
};

}  // namespace frontsteal::sched
