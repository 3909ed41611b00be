// search.hpp — the model checker's interface, free of Relacy: run one scenario under one policy table with
// one search strategy and get a verdict. Implemented in suite_*.cpp (the only files that include Relacy).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "models_check/scenarios.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::model {

// What after() checks. Exactly-once: payloads are rl::var (double processing without ordering is a data race)
// plus a per-item claim counter that asserts on the second run. At-least-once: counters only, lost asserts.
enum class CheckMode { kExactlyOnce, kAtLeastOnce };

enum class SearchKind { kRandom, kContextBound, kFull };

struct SearchConfig {
  SearchKind kind = SearchKind::kRandom;
  std::uint64_t iterations = 100000;  // random search
  unsigned bound = 1;                 // context-bound search
  // Context-bound and full searches: stop exploring after this many executions (0: no cap). A safety net
  // only: with the spin bound the program is finite and the fast tier's searches finish well below it.
  std::uint64_t execution_cap = 0;
  // Tree searches: failed iterations allowed per wait before the execution is discarded (relacy_backend.hpp,
  // SPIN BOUND). 0: unbounded. The random search always runs unbounded.
  unsigned spin_bound = 1;
  unsigned depth_limit = 20000;  // Relacy's execution_depth_limit (scheduling points per execution)
  std::string history_path;      // on failure, replay the failing execution and write its history here
  bool relacy_progress = false;  // let Relacy print its own progress (percent of the search) to stderr
};

// kEarlyQuit: a worker stopped looking for work (read the active count 0 at A3) while an item of the frame
// had not yet run: the termination count failed at what it exists for.
enum class Verdict { kPass, kDuplicate, kLost, kEarlyQuit, kDataRace, kDeadlock, kLivelock, kOtherFailure };

constexpr std::string_view name(Verdict v) {
  switch (v) {
    case Verdict::kPass: return "pass";
    case Verdict::kDuplicate: return "duplicate";
    case Verdict::kLost: return "lost";
    case Verdict::kEarlyQuit: return "early quit";
    case Verdict::kDataRace: return "data race";
    case Verdict::kDeadlock: return "deadlock";
    case Verdict::kLivelock: return "livelock";
    case Verdict::kOtherFailure: return "failure";
  }
  return "?";
}

constexpr std::string_view name(SearchKind k) {
  switch (k) {
    case SearchKind::kRandom: return "random";
    case SearchKind::kContextBound: return "context-bound";
    case SearchKind::kFull: return "full";
  }
  return "?";
}

struct SearchResult {
  Verdict verdict = Verdict::kPass;
  std::string relacy_result;              // Relacy's own name for the result
  SearchKind kind = SearchKind::kRandom;  // the search that produced it
  unsigned bound = 0;                     // its context bound (context-bound searches)
  std::uint64_t iterations = 0;           // executions explored (until the failure, if any)
  std::uint64_t completed = 0;            // tree searches: executions run to the end and checked
  std::uint64_t discarded = 0;            // tree searches: executions discarded by the spin bound (not checked)
  unsigned spin_bound = 0;                // the bound the search ran under (0: unbounded)
  bool capped = false;                    // the search hit SearchConfig::execution_cap: not exhaustive within its bound
  double seconds = 0;
  std::string detail;  // e.g. "item 1 ran twice in frame 1"
};

// Runs `scenario` under current_table() (set it first).
SearchResult run_scenario(const ScenarioSpec& scenario, CheckMode mode, const SearchConfig& config);

}  // namespace frontsteal::model
