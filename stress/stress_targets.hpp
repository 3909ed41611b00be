// stress_targets.hpp — what the stress driver can run: one small adapter per protocol policy and one per
// scheduler of schedulers/registry.hpp, behind one interface, plus planted-defect negative controls.
//
// Adding a target is a few lines: a factory that builds something with run_frame(item function) and
// reseed(lists), plus a row in targets() naming its contract. The driver audits every frame itself.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/frame_stats.hpp"
#include "core/id_range.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/synthetic_work.hpp"
#include "stress/watchdog.hpp"
#include "models_check/table_policy.hpp"
#include "stress/chaos_backend.hpp"
#include "schedulers/registry.hpp"
#include "schedulers/worker_team.hpp"
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

// The stealing scheduler under a watchdog (stress/watchdog.hpp): a case whose frame stops moving ends the run
// with every worker's state instead of hanging the stress tier until ctest's timeout.
template <class Policy, class Backend>
class StealingTarget final : public StressTarget {
 public:
  StealingTarget(WorkerId workers, ItemId items, std::uint64_t seed, std::uint32_t claim_batch = 1)
      : scheduler_({.workers = workers, .items = items, .seed = seed, .claim_batch = claim_batch}),
        watchdog_(watch_workers(scheduler_, "frontsteal-stress: stealing/" + std::string(Policy::kName) + ", P=" +
                                                std::to_string(workers) + ", " + std::to_string(items) + " items")) {}
  const FrameStats& run_frame(const ItemFunction& process) override { return scheduler_.run_frame(process); }
  void reseed(const std::vector<RangeList>& lists) override { scheduler_.reseed(lists); }

 private:
  StealingScheduler<Policy, Backend> scheduler_;
  Watchdog watchdog_;  // after scheduler_: destroyed first, so it never probes a scheduler being torn down
};

struct TargetInfo {
  std::string name;
  Contract contract;
  bool negative_control;  // must be caught: exactly-once claimed, defect planted
  std::function<std::unique_ptr<StressTarget>(WorkerId, ItemId, std::uint64_t)> make;
  // One run of a model-checking scenario (models_check/scenarios.hpp) on real threads; empty for the
  // schedulers that are not the stealing protocol.
  std::function<ExecutionAudit(const model::ScenarioSpec&, std::uint64_t)> run_scenario;
};

// This build runs under ThreadSanitizer: the schedulers whose runtimes are not instrumented (oneTBB, libgomp)
// would report their own synchronization as races, so they are audited by the release build instead.
#if defined(__SANITIZE_THREAD__)
inline constexpr bool kUnderThreadSanitizer = true;
#else
inline constexpr bool kUnderThreadSanitizer = false;
#endif

// Any scheduler of schedulers/ (its own threads; std atomics, so no chaos injection: TSan and the audit check it).
class SchedulerTarget final : public StressTarget {
 public:
  explicit SchedulerTarget(std::unique_ptr<sched::Scheduler> s) : scheduler_(std::move(s)) {}
  const FrameStats& run_frame(const ItemFunction& process) override { return scheduler_->run_frame(process); }
  void reseed(const std::vector<RangeList>&) override {}  // their allocation is their own

 private:
  std::unique_ptr<sched::Scheduler> scheduler_;
};

// Negative control for the scheduler audit: a chunked counter whose claim is a load and a later store instead
// of one fetch_add (a classic lost-update defect), with the window widened so that two workers regularly read
// the same value. No data race (both accesses are atomic): only the exactly-once audit can catch it.
class RacyCounterScheduler final : public sched::Scheduler {
 public:
  RacyCounterScheduler(WorkerId workers, ItemId items)
      : items_(items), slots_(workers), team_(workers, [this](WorkerId w) { work(w); }) {}
  const FrameStats& run_frame(sched::ItemFunctionRef process) override {
    process_ = &process;
    next_.store(0, std::memory_order::relaxed);
    for (auto& s : slots_) s.begin_frame();
    return sched::collect(stats_, slots_, team_.run_frame());
  }
  WorkerId worker_count() const noexcept override { return team_.size(); }

 private:
  void work(WorkerId w) {
    for (;;) {
      const ItemId first = next_.load(std::memory_order::relaxed);  // DEFECT: not one read-modify-write
      if (first >= items_) return;
      spin_work(200);
      // Now and then give the core away inside the window: under load (other tests on every core) the workers
      // rarely overlap in time, and the defect must still show.
      if (first % 8 == 0) std::this_thread::yield();
      next_.store(first + 1, std::memory_order::relaxed);
      slots_[w].run(*process_, first, w);
    }
  }
  ItemId items_;
  std::atomic<ItemId> next_{0};
  std::vector<sched::WorkerSlot> slots_;
  const sched::ItemFunctionRef* process_ = nullptr;
  FrameStats stats_;
  sched::WorkerTeam team_;
};

// Every scheduler of the registry except the stealing ones (stealing_target<Policy> runs those on the chaos
// backend), and the racy counter.
inline std::vector<TargetInfo> scheduler_targets() {
  std::vector<TargetInfo> all;
  for (const sched::SchedulerInfo& info : sched::scheduler_registry()) {
    if (info.name.rfind("stealing/", 0) == 0) continue;
    if (kUnderThreadSanitizer && !info.tsan_clean) continue;
    all.push_back({info.name,
                   info.contract,
                   false,
                   [&info](WorkerId p, ItemId n, std::uint64_t seed) -> std::unique_ptr<StressTarget> {
                     return std::make_unique<SchedulerTarget>(info.make({.workers = p, .items = n, .seed = seed}, {}));
                   },
                   {}});
  }
  all.push_back({"counter-racy",
                 Contract::kExactlyOnce,
                 true,
                 [](WorkerId p, ItemId n, std::uint64_t) -> std::unique_ptr<StressTarget> {
                   return std::make_unique<SchedulerTarget>(std::make_unique<RacyCounterScheduler>(p, n));
                 },
                 {}});
  return all;
}

// `claim_batch` > 1: the owners claim that many items per handshake (Owner::try_claim_up_to), named "+batchN".
template <class Policy, class Backend = ChaosBackend>
TargetInfo stealing_target(std::uint32_t claim_batch = 1) {
  const std::string batch = claim_batch > 1 ? "+batch" + std::to_string(claim_batch) : "";
  return {std::string("stealing/") + std::string(Policy::kName) + batch, Policy::kContract,
          Policy::defects() != Defect::kNone,
          [claim_batch](WorkerId p, ItemId n, std::uint64_t seed) -> std::unique_ptr<StressTarget> {
            return std::make_unique<StealingTarget<Policy, Backend>>(p, n, seed, claim_batch);
          },
          [](const model::ScenarioSpec& spec, std::uint64_t seed) {
            return run_scenario_on_threads<Policy, Backend>(spec, seed);
          }};
}

inline std::vector<TargetInfo> targets() {
  std::vector<TargetInfo> all{stealing_target<SeqCst>(),
                              stealing_target<Paper>(),
                              stealing_target<Fenced>(),
                              stealing_target<Minimal>(),
                              stealing_target<Fenced>(4),
                              stealing_target<BrokenSkipsReread>(),
                              stealing_target<BrokenNoTransient>(),
                              stealing_target<BrokenBatchIgnoresEnd>(4)};
  if (membarrier_status().available) all.insert(all.begin() + 3, stealing_target<Asymmetric>());
  for (auto& t : scheduler_targets()) all.push_back(std::move(t));
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
