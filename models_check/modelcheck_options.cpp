// modelcheck_options.cpp — frontsteal-modelcheck's options and the budgets and scenarios they choose.
#include "models_check/modelcheck_options.hpp"

#include <algorithm>
#include <string>

#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "reporting/command_line.hpp"

namespace frontsteal::model::stealing {

namespace {

constexpr const char* kDescription =
    R"(Model-checks the load-stealing protocol of core/ with Relacy: every scenario of models_check/scenarios.hpp
under every chosen policy, with random and context-bound searches; optionally a memory-order mutation kill
matrix and the certificate of the Minimal policy. Writes markdown and JSON results; exits 1 on any verdict
that differs from the expected-verdict table (models_check/expected_verdicts.hpp), 2 for bad usage.)";
constexpr const char* kFooter = R"(
Tiers: fast: 1e5 random iterations, complete context bound 1, bound 2 for 2-thread scenarios, 2e4 random
iterations per mutant, then complete bound 1 on 2-thread scenarios; slow: 1e6 random iterations, bounds 1
and 2, bound 3 for 2-thread scenarios, 1e5 per mutant.
Searches: random, bound1, bound2, bound3, full; boundN:T only for scenarios of at most T threads.
Bounds, stated honestly: Relacy keeps a few stores per atomic and never produces load buffering. Context-bound
searches run the finite program of the spin bound (each wait may fail --spin-bound times, frame waits once
more; longer waits are discarded and counted) and are exhaustive within their bound unless "capped"; the
random search runs the unbounded program. A pass is a bounded search, not a proof.)";

// A search name: random, bound1..3 or full, optionally ":T" (only scenarios of at most T threads).
CLI::Validator search_validator() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const std::string base = s.substr(0, s.find(':'));
        if (base == "random" || base == "bound1" || base == "bound2" || base == "bound3" || base == "full") return {};
        return "unknown search '" + s + "' (random, bound1, bound2, bound3, full; boundN:T for at most T threads)";
      },
      "SEARCH");
}

}  // namespace

std::vector<PolicyTable> known_policies() { return known_stealing_policies(); }

std::optional<PolicyTable> policy_by_name(std::string_view name) {
  for (auto& p : known_policies()) {
    if (p.name == name) return p;
  }
  return std::nullopt;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> policy_names{"all"}, scenario_names{"all"};
  for (const auto& p : known_policies()) policy_names.push_back(p.name);
  for (const auto& s : scenarios()) scenario_names.emplace_back(s.name);
  std::vector<std::string> policies{"all"}, scenario_list{"all"};
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--tier", o.tier, "fast or slow (see Tiers)")->check(CLI::IsMember({"fast", "slow"}));
  cli.app()
      .add_option("--policy", policies, "comma-separated policy names, or all")
      ->delimiter(',')
      ->check(CLI::IsMember(policy_names).description(""));
  cli.app()
      .add_option("--scenario", scenario_list, "comma-separated scenario names, or all")
      ->delimiter(',')
      ->check(CLI::IsMember(scenario_names).description(""));
  auto* search = cli.app()
                     .add_option("--search", o.searches,
                                 "comma-separated searches (see Searches); the slow "
                                 "tier's default is random,bound1,bound2,bound3:2")
                     ->delimiter(',')
                     ->check(search_validator());
  cli.app()
      .add_option("--iterations", o.iterations, "random-search iterations (overrides the tier)")
      ->check(CLI::PositiveNumber);
  cli.app()
      .add_option("--cap", o.cap,
                  "safety cap: executions after which a context-bound or full search stops "
                  "(overrides the tier: fast 1e7, slow 1e8); results say \"capped\" when a search stopped there")
      ->check(CLI::PositiveNumber);
  cli.option("--mutants", o.mutants, "also run the kill matrix of every one-step weakening of this policy")
      ->check(CLI::IsMember(std::vector<std::string>(policy_names.begin() + 1, policy_names.end())).description(""));
  cli.app()
      .add_option("--mutant-iterations", o.mutant_iterations,
                  "random-search iterations per mutant and scenario (overrides the tier)")
      ->check(CLI::PositiveNumber);
  cli.app()
      .add_option("--mutant-search", o.mutant_searches,
                  "searches run against each mutant, in order, up to the "
                  "first kill [default: fast random,bound1:2; slow random,bound1]")
      ->delimiter(',')
      ->check(search_validator());
  cli.flag("--certify", o.certify, "also certify Minimal: every one-step weakening must be killed");
  cli.option("--derive-minimal", o.derive_base,
             "greedily weaken this policy while every scenario passes; print the "
             "resulting table")
      ->check(CLI::IsMember(std::vector<std::string>(policy_names.begin() + 1, policy_names.end())).description(""));
  bool no_verdicts = false;
  cli.flag("--no-verdicts", no_verdicts, "skip the policy x scenario verdict table");
  cli.option("--spin-bound", o.spin_bound,
             "tree searches: failed iterations allowed per wait or idle round before "
             "the execution is discarded (0: unbounded, the searches then hit the cap)")
      ->check(CLI::Range(0u, 16u));
  cli.option("--depth", o.depth, "Relacy execution_depth_limit")->check(CLI::PositiveNumber);
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  o.verdicts = !no_verdicts;
  auto chosen = [](const std::vector<std::string>& names, const std::vector<std::string>& all) {
    return std::find(names.begin(), names.end(), "all") != names.end()
               ? std::vector<std::string>(all.begin() + 1, all.end())
               : names;
  };
  o.policies = chosen(policies, policy_names);
  if (std::find(scenario_list.begin(), scenario_list.end(), "all") == scenario_list.end()) o.scenarios = scenario_list;
  if (o.tier == "slow" && search->count() == 0) o.searches = {"random", "bound1", "bound2", "bound3:2"};
  if (o.mutant_searches.empty()) o.mutant_searches = {"random", o.tier == "slow" ? "bound1" : "bound1:2"};
  return o;
}

std::uint64_t random_iterations(const Options& o) { return o.iterations.value_or(o.tier == "slow" ? 1000000 : 100000); }
std::uint64_t execution_cap(const Options& o) { return o.cap.value_or(o.tier == "slow" ? 100000000 : 10000000); }
std::uint64_t mutant_iterations(const Options& o) {
  return o.mutant_iterations.value_or(o.tier == "slow" ? 100000 : 20000);
}

bool applies(const std::string& search, const ScenarioSpec& scenario) {
  const auto colon = search.find(':');
  return colon == std::string::npos ||
         scenario.threads() <= static_cast<unsigned>(std::stoul(search.substr(colon + 1)));
}

SearchConfig config_for(const std::string& search, std::uint64_t iterations, const Options& o) {
  SearchConfig c;
  c.depth_limit = o.depth;
  c.spin_bound = o.spin_bound;
  c.execution_cap = execution_cap(o);
  c.iterations = iterations;
  const std::string base = search.substr(0, search.find(':'));  // "full:2" is the full search on two threads
  if (base == "random") {
    c.kind = SearchKind::kRandom;
  } else if (base == "full") {
    c.kind = SearchKind::kFull;
  } else {
    c.kind = SearchKind::kContextBound;
    c.bound = static_cast<unsigned>(search[5] - '0');  // "boundN" or "boundN:T"
  }
  return c;
}

std::vector<const ScenarioSpec*> chosen_scenarios(const Options& o) {
  std::vector<const ScenarioSpec*> out;
  for (const auto& s : scenarios()) {
    if (o.scenarios.empty() || std::find(o.scenarios.begin(), o.scenarios.end(), s.name) != o.scenarios.end()) {
      out.push_back(&s);
    }
  }
  return out;
}

}  // namespace frontsteal::model::stealing
