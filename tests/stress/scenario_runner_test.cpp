// The model checker's scenarios on real threads (stress/scenario_runner.hpp): the same configurations Relacy
// explores, executed many times each. Exactly-once policies must never duplicate or lose; Paper must never
// lose; the negative controls, under chaos, must be caught in at least one scenario.
#include "stress/scenario_runner.hpp"

#include <catch2/catch.hpp>

#include <chrono>

#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "core/std_backend.hpp"
#include "stress/chaos_backend.hpp"

namespace fs = frontsteal;
using fs::model::scenarios;

namespace {
constexpr int kRunsPerScenario = 300;
}

TEMPLATE_TEST_CASE("every model-checking scenario holds on real threads", "[stress][scenario]", fs::SeqCst, fs::Fenced,
                   fs::Minimal, fs::Paper) {
  for (const auto& spec : scenarios()) {
    fs::ExecutionAudit total;
    for (int run = 0; run < kRunsPerScenario; ++run) {
      const auto a = fs::stress::run_scenario_on_threads<TestType, fs::StdBackend>(spec, run + 1);
      total.lost += a.lost;
      total.duplicated += a.duplicated;
    }
    INFO(TestType::kName << " / " << spec.name << ": lost " << total.lost << ", duplicated " << total.duplicated);
    CHECK(total.lost == 0);
    if (TestType::kContract == fs::Contract::kExactlyOnce) CHECK(total.duplicated == 0);
  }
}

TEMPLATE_TEST_CASE("negative controls are caught in the scenarios under chaos", "[stress][scenario][negative]",
                   fs::BrokenSkipsReread, fs::BrokenNoTransient) {
  fs::stress::chaos_settings() = {200000, 7};  // 20% of labelled accesses perturbed: windows wide open
  // Runs until the defect shows: how many runs that takes depends on how the machine's load schedules the
  // threads, so the bound is wall time (60 s), there only to end the test if the audit is blind.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::uint64_t duplicated = 0;
  int runs = 0;
  while (duplicated == 0 && std::chrono::steady_clock::now() < deadline) {
    ++runs;
    for (const auto& spec : scenarios()) {
      duplicated += fs::stress::run_scenario_on_threads<TestType, fs::stress::ChaosBackend>(spec, runs).duplicated;
    }
  }
  fs::stress::chaos_settings() = {};
  INFO(TestType::kName << " after " << runs << " runs of every scenario");
  CHECK(duplicated > 0);
}
