// modelcheck_options.hpp — what one run of frontsteal-modelcheck checks and how hard: its options (CLI11,
// through reporting/), the policies it knows, and the search budgets and scenarios they choose. Free of Relacy.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::model::stealing {

inline constexpr const char* kProgram = "frontsteal-modelcheck";

struct Options {
  std::string tier = "fast";
  std::vector<std::string> policies;
  std::vector<std::string> scenarios;  // empty: every scenario
  // Fast tier: every cell gets the complete bound-1 search and two-thread scenarios the complete bound-2
  // search (three-thread scenarios take minutes each at bound 2: slow tier). "boundN:T" limits a search
  // to scenarios with at most T threads.
  std::vector<std::string> searches{"random", "bound1", "bound2:2"};
  std::optional<std::uint64_t> iterations;
  std::optional<std::uint64_t> mutant_iterations;
  std::optional<std::uint64_t> cap;
  std::string mutants;
  std::vector<std::string> mutant_searches;  // empty: the tier's
  bool certify = false;
  std::string derive_base;
  bool verdicts = true;
  unsigned depth = 20000;
  unsigned spin_bound = 1;
  std::string out = "out/modelcheck";
  bool quiet = false;
};

// Parses argv: --help exits 0, a mistake exits 2 naming the flag; fills in the tier's defaults.
Options parse(int argc, char** argv);

// Every policy the checker knows (the sound ones, Paper, the planted defects), and one of them by name.
std::vector<PolicyTable> known_policies();
std::optional<PolicyTable> policy_by_name(std::string_view name);

// The tier's budgets unless the options override them.
std::uint64_t random_iterations(const Options& o);
std::uint64_t execution_cap(const Options& o);  // a safety net only: spin-bounded searches finish far below it
std::uint64_t mutant_iterations(const Options& o);

// "boundN:T" applies only to scenarios with at most T threads; every other search to every scenario.
bool applies(const std::string& search, const ScenarioSpec& scenario);
// The SearchConfig of a search name ("random", "boundN[:T]", "full[:T]") with the options' depth, spin bound, cap.
SearchConfig config_for(const std::string& search, std::uint64_t iterations, const Options& o);
std::vector<const ScenarioSpec*> chosen_scenarios(const Options& o);

}  // namespace frontsteal::model::stealing
