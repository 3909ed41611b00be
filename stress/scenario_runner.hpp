// scenario_runner.hpp — the model checker's scenarios (models_check/scenarios.hpp) on real threads.
//
// One scenario source drives three harnesses: Relacy explores each scenario's interleavings
// (models_check/protocol_suite.hpp), this runner executes the very same configuration on std::threads —
// from Catch2 (tests/stress/scenario_runner_test.cpp) and from the stress driver (`frontsteal-stress
// --scenarios`, under ThreadSanitizer and chaos). The thread roles mirror ProtocolSuite: each worker runs
// its frames; with `with_caller`, one more thread releases the frames, waits for them and reads every
// worker's statistics, as StealingScheduler does.
// Every run is watched (stress/watchdog.hpp): a scenario whose frame stops moving ends the process with each
// worker's state, naming the scenario and the policy, instead of hanging the test or the stress tier.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/frame_loop.hpp"
#include "stress/watchdog.hpp"
#include "models_check/scenarios.hpp"

namespace frontsteal::stress {

// Runs `spec` once on real threads; returns the audit of all its frames together (items × frames runs).
template <class Policy, class Backend>
ExecutionAudit run_scenario_on_threads(const model::ScenarioSpec& spec, std::uint64_t seed) {
  StealingWorkers<Backend, Policy> core(spec.workers, spec.items, seed);
  core.reseed(spec.initial);
  core.set_claim_batch(spec.claim_batch);
  for (WorkerId w = 0; w < spec.victims.size(); ++w) core.set_victims(w, spec.victims[w]);
  // One counter per (frame, item), so a duplicate in one frame cannot hide a loss in another.
  const ItemId cells = static_cast<ItemId>(spec.items * spec.frames);
  ExecutionCounter runs(cells);
  if (!spec.with_caller) core.release_frame(spec.frames);
  const Watchdog dog = watch_workers(core, "scenario " + std::string(spec.name) + " (policy " +
                                               std::string(Policy::kName) + ", seed " + std::to_string(seed) + ")");

  std::vector<std::thread> threads;
  for (WorkerId w = 0; w < spec.workers; ++w) {
    threads.emplace_back([&, w] {
      for (std::uint32_t k = 1; k <= spec.frames; ++k) {
        core.await_frame_start(k);
        auto process = [&, k](ItemId id, WorkerId) { runs.record((k - 1) * spec.items + id); };
        core.run_frame(w, k, process);
      }
    });
  }
  if (spec.with_caller) {
    threads.emplace_back([&] {
      for (std::uint32_t k = 1; k <= spec.frames; ++k) {
        core.release_frame(k);
        core.await_frame_done(k);
        for (WorkerId w = 0; w < spec.workers; ++w) {
          (void)core.stats(w);
          (void)core.failure(w);
        }
      }
    });
  }
  for (auto& t : threads) t.join();
  return runs.audit_and_reset();
}

}  // namespace frontsteal::stress
