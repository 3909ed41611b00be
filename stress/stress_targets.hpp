// stress_targets.hpp — what the stress driver can run: one small adapter per protocol policy (and, later, per
// scheduler), behind one interface.
//
// Adding a target is a few lines: a factory that builds something with run_frame(item function) and
// reseed(lists), plus a row in targets() naming its contract. The driver audits every frame itself.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/frame_stats.hpp"
#include "core/id_range.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "models_check/table_policy.hpp"
#include "stress/chaos_backend.hpp"
#include "stress/scenario_runner.hpp"

namespace frontsteal::stress {

using ItemFunction = std::function<void(ItemId, WorkerId)>;

class StressTarget {
 public:
  virtual ~StressTarget() = default;
  // Runs one frame; throws ItemError if an item function threw (after the frame completed).
  virtual const FrameStats& run_frame(const ItemFunction& process) = 0;
  virtual void reseed(const std::vector<RangeList>& lists) = 0;
};

template <class Policy, class Backend>
class StealingTarget final : public StressTarget {
 public:
  StealingTarget(WorkerId workers, ItemId items, std::uint64_t seed)
      : scheduler_({.workers = workers, .items = items, .seed = seed}) {}
  const FrameStats& run_frame(const ItemFunction& process) override { return scheduler_.run_frame(process); }
  void reseed(const std::vector<RangeList>& lists) override { scheduler_.reseed(lists); }

 private:
  StealingScheduler<Policy, Backend> scheduler_;
};

struct TargetInfo {
  std::string name;
  Contract contract;
  bool negative_control;  // must be caught: exactly-once claimed, defect planted
  std::function<std::unique_ptr<StressTarget>(WorkerId, ItemId, std::uint64_t)> make;
  // One run of a model-checking scenario (models_check/scenarios.hpp) on real threads.
  std::function<ExecutionAudit(const model::ScenarioSpec&, std::uint64_t)> run_scenario;
};

template <class Policy, class Backend = ChaosBackend>
TargetInfo stealing_target() {
  return {std::string("stealing/") + std::string(Policy::kName), Policy::kContract,
          Policy::defects() != Defect::kNone,
          [](WorkerId p, ItemId n, std::uint64_t seed) -> std::unique_ptr<StressTarget> {
            return std::make_unique<StealingTarget<Policy, Backend>>(p, n, seed);
          },
          [](const model::ScenarioSpec& spec, std::uint64_t seed) {
            return run_scenario_on_threads<Policy, Backend>(spec, seed);
          }};
}

inline std::vector<TargetInfo> targets() {
  std::vector<TargetInfo> all{stealing_target<SeqCst>(),           stealing_target<Paper>(),
                              stealing_target<Fenced>(),           stealing_target<Minimal>(),
                              stealing_target<BrokenSkipsReread>(), stealing_target<BrokenNoTransient>()};
  if (membarrier_status().available) all.insert(all.begin() + 3, stealing_target<Asymmetric>());
  return all;
}

// A policy read from a run-time table (models_check/table_policy.hpp) on the plain std backend: used to
// measure the duplicate rate of each memory-order mutant on real hardware, without chaos.
inline TargetInfo table_target(const model::PolicyTable& table) {
  return {"stealing/" + table.name, table.contract, false,
          [](WorkerId p, ItemId n, std::uint64_t seed) -> std::unique_ptr<StressTarget> {
            return std::make_unique<StealingTarget<model::TablePolicy, StdBackend>>(p, n, seed);
          },
          [](const model::ScenarioSpec& spec, std::uint64_t seed) {
            return run_scenario_on_threads<model::TablePolicy, StdBackend>(spec, seed);
          }};
}

}  // namespace frontsteal::stress
