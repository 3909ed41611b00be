// protocol_suite.hpp — one Relacy test suite runs any scenario (scenarios.hpp) under any policy table.
//
// The thread count is the only compile-time parameter Relacy needs, so ProtocolSuite<Threads, Mode> has four
// instantiations in all (2 or 3 threads, two check modes), spread over suite_*.cpp for parallel builds.
// Scenario, policy and mode come from run-time globals set before rl::simulate (Relacy constructs a fresh
// suite for every execution, but does not reset globals; these are only read during a run).
#pragma once

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <string_view>

#include "core/frame_loop.hpp"
#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"

#include "models_check/relacy_backend.hpp"  // last: it includes relacy.hpp

namespace frontsteal::model {

struct SuiteContext {
  const ScenarioSpec* scenario = nullptr;
  // Execution cap for tree searches: past it, executions do nothing, so the search tree collapses and
  // Relacy's scheduler finishes. Relacy does not reset globals between executions, which this relies on.
  std::uint64_t execution_cap = 0;
  std::uint64_t executions = 0;
  // Tree searches run the finite program (relacy_backend.hpp, SPIN BOUND): executions that reached after()
  // with their checks run, and executions discarded because a wait exceeded the bound (checks skipped).
  std::uint64_t completed = 0;
  std::uint64_t discarded = 0;
  // Ghost state for the termination check, plain variables: Relacy runs every thread on fibers of one OS
  // thread, so they follow the interleaving itself, not any thread's view of memory.
  std::uint32_t frame_of_thread[SpinBound::kMaxThreads] = {};
  std::uint32_t items_run[kMaxScenarioFrames] = {};  // distinct items that started running in each frame
  // Written by the failing execution just before it fails the test, read after rl::simulate returns.
  Verdict failure = Verdict::kPass;
  char failure_detail[160] = {};
};

// Relacy's allocator makes every free() a two-way choice point (free now, or defer so a later allocation
// cannot reuse the address: it hunts use-after-free). The stealing protocol frees no shared memory; the
// frees in an execution are the frame loop's private bookkeeping (logs, next lists) and the suite's own
// teardown — about twenty per execution, which multiplies every interleaving by 2^20 and kept the tree
// searches from finishing even with bounded waits. So the protocol suite sends its heap traffic straight to
// malloc/free (Relacy does the same for its own allocations, through this counter). The counter is protected
// in rl::context; a pointer to member named through a derived class is the standard way to reach it.
struct HeapOutsideRelacy : rl::context {
  static int& counter() { return rl::ctx().*(&HeapOutsideRelacy::disable_alloc_); }
};

inline SuiteContext& suite_context() {
  static SuiteContext c;
  return c;
}

inline void fail_with(Verdict v, const char* detail, const rl::debug_info& where) {
  suite_context().failure = v;
  std::snprintf(suite_context().failure_detail, sizeof suite_context().failure_detail, "%s", detail);
  rl::ctx().fail_test(detail, rl::test_result_user_assert_failed, where);
}

// A worker read the active count 0 at A3 and is about to stop looking for work: by the count's invariant
// (I-T, active_workers.hpp) every item of its frame has run by now. If one has not, it is still in a list
// or in a thief's share, and this worker quits while stealable work remains.
inline void check_idle_seen() {
  SuiteContext& ctx = suite_context();
  const std::uint32_t k = ctx.frame_of_thread[rl::thread_index()];
  if (k == 0 || ctx.items_run[k - 1] == ctx.scenario->items) return;
  char text[120];
  std::snprintf(text, sizeof text, "a worker stopped looking for work in frame %u with %u of %u items not yet run", k,
                ctx.scenario->items - ctx.items_run[k - 1], ctx.scenario->items);
  fail_with(Verdict::kEarlyQuit, text, $);
}

template <rl::thread_id_t Threads, CheckMode Mode>
struct ProtocolSuite : rl::test_suite<ProtocolSuite<Threads, Mode>, Threads> {
  using Workers = StealingWorkers<RelacyBackend, TablePolicy>;

  const ScenarioSpec& spec = *suite_context().scenario;
  std::unique_ptr<Workers> core;
  rl::var<int> payload[kMaxScenarioItems];                      // exactly-once mode: touched by each run
  rl::atomic<int> runs[kMaxScenarioFrames][kMaxScenarioItems];  // runs of each item in each frame
  rl::var<int> frame_input[kMaxScenarioFrames];                 // caller -> workers (E1 -> E2)

  bool collapsed = false;  // past the execution cap: this execution does nothing

  // The allocator bypass spans the whole execution: from before() (which allocates `core`) to the
  // destructor (which frees it). A failing execution never reaches the destructor, but it ends the search,
  // and each rl::simulate builds a fresh context.
  ~ProtocolSuite() {
    core.reset();
    --HeapOutsideRelacy::counter();
  }

  void before() {
    ++HeapOutsideRelacy::counter();
    SuiteContext& ctx = suite_context();
    spin_bound().discarded = false;
    if (ctx.execution_cap != 0 && ++ctx.executions > ctx.execution_cap) {
      collapsed = true;
      return;
    }
    for (auto& f : ctx.frame_of_thread) f = 0;
    for (auto& n : ctx.items_run) n = 0;
    idle_seen_hook = &check_idle_seen;
    core = std::make_unique<Workers>(spec.workers, spec.items, 1);
    core->reseed(spec.initial);
    core->set_claim_batch(spec.claim_batch);
    for (WorkerId w = 0; w < spec.victims.size(); ++w) core->set_victims(w, spec.victims[w]);
    for (ItemId i = 0; i < kMaxScenarioItems; ++i) {
      payload[i]($) = 0;
      for (std::uint32_t k = 0; k < kMaxScenarioFrames; ++k) runs[k][i].store(0, rl::mo_relaxed, $);
    }
    if (!spec.with_caller) core->release_frame(spec.frames);  // frames pre-released: no caller thread
  }

  void thread(unsigned index) {
    if (collapsed) return;
    // Landing point for a discarded execution (SPIN BOUND): the thread body ends here, nothing else runs.
    if (setjmp(spin_bound().exits[index]) != 0) return;
    if (spec.with_caller && index == spec.workers) return caller();
    for (std::uint32_t k = 1; k <= spec.frames; ++k) {
      core->await_frame_start(k);
      suite_context().frame_of_thread[index] = k;
      auto process = [this, k](ItemId id, WorkerId) { run_item(id, k); };
      core->run_frame(static_cast<WorkerId>(index), k, process);
    }
  }

  // The caller: publish the frame's input, release the frame, wait for it, read every payload.
  void caller() {
    for (std::uint32_t k = 1; k <= spec.frames; ++k) {
      frame_input[k - 1]($) = static_cast<int>(k);
      core->release_frame(k);
      core->await_frame_done(k);
      for (WorkerId w = 0; w < spec.workers; ++w) {  // as StealingScheduler does after every frame
        (void)core->stats(w);
        (void)core->failure(w);
      }
      for (ItemId i = 0; i < spec.items; ++i) {
        const int seen = payload[i]($);
        if (Mode == CheckMode::kExactlyOnce && seen != static_cast<int>(k)) {
          fail_with(Verdict::kLost, "caller: an item's payload is not up to date after the frame", $);
        }
      }
    }
  }

  void run_item(ItemId id, std::uint32_t k) {
    if (spec.with_caller) {
      const int input = frame_input[k - 1]($);
      if (input != static_cast<int>(k)) fail_with(Verdict::kOtherFailure, "worker read a stale frame input", $);
    }
    const int earlier = runs[k - 1][id].fetch_add(1, rl::mo_relaxed, $);
    if (earlier == 0) ++suite_context().items_run[k - 1];
    if (Mode == CheckMode::kExactlyOnce) {
      if (earlier != 0) {
        char text[96];
        std::snprintf(text, sizeof text, "item %u ran twice in frame %u", id, k);
        fail_with(Verdict::kDuplicate, text, $);
      }
      payload[id]($) = payload[id]($) + 1;  // a second, unordered run would also be a data race here
    }
  }

  void after() {
    if (collapsed) return;
    if (spin_bound().discarded) {  // a wait exceeded the bound: not a complete execution, nothing to check
      ++suite_context().discarded;
      return;
    }
    ++suite_context().completed;
    for (std::uint32_t k = 1; k <= spec.frames; ++k) {
      for (ItemId i = 0; i < spec.items; ++i) {
        if (runs[k - 1][i].load(rl::mo_relaxed, $) == 0) {
          char text[96];
          std::snprintf(text, sizeof text, "item %u never ran in frame %u", i, k);
          fail_with(Verdict::kLost, text, $);
        }
      }
    }
  }
};

inline Verdict classify(rl::test_result_e r) {
  switch (r) {
    case rl::test_result_success: return Verdict::kPass;
    case rl::test_result_data_race: return Verdict::kDataRace;
    case rl::test_result_deadlock: return Verdict::kDeadlock;
    case rl::test_result_livelock: return Verdict::kLivelock;
    case rl::test_result_user_assert_failed:
      return suite_context().failure == Verdict::kPass ? Verdict::kOtherFailure : suite_context().failure;
    default: return Verdict::kOtherFailure;
  }
}

// Runs one suite under current_table(); `name` names the scenario in histories. The suite reads its scenario
// from a global the caller set.
template <class Suite>
SearchResult simulate_suite(std::string_view name, const SearchConfig& config) {
  suite_context().failure = Verdict::kPass;
  suite_context().failure_detail[0] = '\0';
  suite_context().executions = 0;
  suite_context().completed = 0;
  suite_context().discarded = 0;
  suite_context().execution_cap = config.kind == SearchKind::kRandom ? 0 : config.execution_cap;
  // The spin bound makes tree searches finite; the random search keeps the unbounded program, so it still
  // reports a livelock past the depth limit.
  spin_bound().k = config.kind == SearchKind::kRandom ? 0 : config.spin_bound;

  std::ofstream quiet("/dev/null");  // Relacy's own printing; an ofstream, never a stringstream (see notes)
  rl::test_params p;
  p.output_stream = &quiet;
  p.progress_stream = config.relacy_progress ? &std::cerr : &quiet;
  p.execution_depth_limit = config.depth_limit;
  switch (config.kind) {
    case SearchKind::kRandom:
      p.search_type = rl::sched_random;
      p.iteration_count = config.iterations;
      break;
    case SearchKind::kContextBound:
      p.search_type = rl::sched_bound;
      p.context_bound = config.bound;
      break;
    case SearchKind::kFull: p.search_type = rl::sched_full; break;
  }
  const auto start = std::chrono::steady_clock::now();
  rl::simulate<Suite>(p);  // returns whether the result matched the suite's expectation (success); we
                           // classify p.test_result ourselves, so the return value carries no extra news
  SearchResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.verdict = classify(p.test_result);
  r.relacy_result = rl::test_result_str(p.test_result);
  r.iterations = p.stop_iteration;
  if (suite_context().execution_cap != 0 && suite_context().executions > suite_context().execution_cap) {
    r.capped = true;
    r.iterations = suite_context().execution_cap;
  }
  r.detail = suite_context().failure_detail;
  r.kind = config.kind;
  r.bound = config.kind == SearchKind::kContextBound ? config.bound : 0;
  r.completed = suite_context().completed;
  r.discarded = suite_context().discarded;
  r.spin_bound = spin_bound().k;
  if (r.verdict == Verdict::kPass && config.kind != SearchKind::kRandom && r.completed == 0) {
    // Every execution was discarded: the search checked nothing (a wait that can never end looks like this).
    r.verdict = Verdict::kOtherFailure;
    r.detail = "vacuous: every execution was discarded by the spin bound";
  }

  if (r.verdict != Verdict::kPass && !config.history_path.empty()) {
    // Replay exactly the failing execution with history collection on.
    std::ofstream history(config.history_path);
    rl::test_params replay;
    replay.output_stream = &history;
    replay.progress_stream = &quiet;
    replay.execution_depth_limit = config.depth_limit;
    replay.search_type = p.search_type;
    replay.context_bound = p.context_bound;
    replay.iteration_count = p.search_type == rl::sched_random ? config.iterations : 0;
    replay.initial_state = p.final_state;
    suite_context().execution_cap = 0;  // the replayed execution must run in full
    // spin_bound().k stays as in the search: the replay must take the same path, discards included.
    replay.collect_history = true;
    replay.output_history = true;
    history << "scenario " << name << " under " << current_table().name << ": " << r.relacy_result
            << (r.detail.empty() ? "" : " — ") << r.detail << "\n";
    rl::simulate<Suite>(replay);
  }
  return r;
}

template <class Suite>
SearchResult simulate_suite(const ScenarioSpec& scenario, const SearchConfig& config) {
  suite_context().scenario = &scenario;
  return simulate_suite<Suite>(scenario.name, config);
}

}  // namespace frontsteal::model
