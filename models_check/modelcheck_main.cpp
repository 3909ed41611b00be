// frontsteal-modelcheck — model-check the stealing protocol with Relacy: verdicts per policy and scenario,
// a memory-order mutation kill matrix, and the certificate of the Minimal policy.
//
// This file never includes Relacy (suite_*.cpp do); it drives run_scenario() and writes the results.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "models_check/report_text.hpp"
#include "models_check/expected_verdicts.hpp"
#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif

namespace fs = frontsteal;
namespace report = frontsteal::report;
using namespace frontsteal;
using namespace frontsteal::model;

namespace {

constexpr const char* kProgram = "frontsteal-modelcheck";
constexpr const char* kDescription = R"(Model-checks the load-stealing protocol of core/ with Relacy: every scenario of models_check/scenarios.hpp
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

struct Options {
  std::string tier = "fast";
  std::vector<std::string> policies;
  std::vector<std::string> scenarios;
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

// ---- the policies the checker knows ------------------------------------------------------------------------
std::vector<PolicyTable> known_policies() {
  return {table_of<fs::SeqCst>(),   table_of<fs::Paper>(),   table_of<fs::Fenced>(),
          table_of<fs::Asymmetric>(), table_of<fs::Minimal>(), table_of<fs::BrokenSkipsReread>(),
          table_of<fs::BrokenNoTransient>(), table_of<fs::BrokenJoinsLate>(),
          table_of<fs::BrokenShareLowerBound>()};
}

std::optional<PolicyTable> policy_by_name(std::string_view name) {
  for (auto& p : known_policies()) {
    if (p.name == name) return p;
  }
  return std::nullopt;
}

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

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> policy_names{"all"}, scenario_names{"all"};
  for (const auto& p : known_policies()) policy_names.push_back(p.name);
  for (const auto& s : scenarios()) scenario_names.emplace_back(s.name);
  std::vector<std::string> policies{"all"}, scenario_list{"all"};
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--tier", o.tier, "fast or slow (see Tiers)")->check(CLI::IsMember({"fast", "slow"}));
  cli.app().add_option("--policy", policies, "comma-separated policy names, or all")
      ->delimiter(',')->check(CLI::IsMember(policy_names).description(""));
  cli.app().add_option("--scenario", scenario_list, "comma-separated scenario names, or all")
      ->delimiter(',')->check(CLI::IsMember(scenario_names).description(""));
  auto* search = cli.app().add_option("--search", o.searches, "comma-separated searches (see Searches); the slow "
                                      "tier's default is random,bound1,bound2,bound3:2")
                     ->delimiter(',')->check(search_validator());
  cli.app().add_option("--iterations", o.iterations, "random-search iterations (overrides the tier)")
      ->check(CLI::PositiveNumber);
  cli.app().add_option("--cap", o.cap, "safety cap: executions after which a context-bound or full search stops "
                       "(overrides the tier: fast 1e7, slow 1e8); results say \"capped\" when a search stopped there")
      ->check(CLI::PositiveNumber);
  cli.option("--mutants", o.mutants, "also run the kill matrix of every one-step weakening of this policy")
      ->check(CLI::IsMember(std::vector<std::string>(policy_names.begin() + 1, policy_names.end())).description(""));
  cli.app().add_option("--mutant-iterations", o.mutant_iterations,
                       "random-search iterations per mutant and scenario (overrides the tier)")->check(CLI::PositiveNumber);
  cli.app().add_option("--mutant-search", o.mutant_searches, "searches run against each mutant, in order, up to the "
                       "first kill [default: fast random,bound1:2; slow random,bound1]")
      ->delimiter(',')->check(search_validator());
  cli.flag("--certify", o.certify, "also certify Minimal: every one-step weakening must be killed");
  cli.option("--derive-minimal", o.derive_base, "greedily weaken this policy while every scenario passes; print the "
             "resulting table")->check(CLI::IsMember(std::vector<std::string>(policy_names.begin() + 1, policy_names.end())).description(""));
  bool no_verdicts = false;
  cli.flag("--no-verdicts", no_verdicts, "skip the policy x scenario verdict table");
  cli.option("--spin-bound", o.spin_bound, "tree searches: failed iterations allowed per wait or idle round before "
             "the execution is discarded (0: unbounded, the searches then hit the cap)")->check(CLI::Range(0u, 16u));
  cli.option("--depth", o.depth, "Relacy execution_depth_limit")->check(CLI::PositiveNumber);
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  o.verdicts = !no_verdicts;
  auto chosen = [](const std::vector<std::string>& names, const std::vector<std::string>& all) {
    return std::find(names.begin(), names.end(), "all") != names.end()
               ? std::vector<std::string>(all.begin() + 1, all.end()) : names;
  };
  o.policies = chosen(policies, policy_names);
  if (std::find(scenario_list.begin(), scenario_list.end(), "all") == scenario_list.end()) o.scenarios = scenario_list;
  if (o.tier == "slow" && search->count() == 0) o.searches = {"random", "bound1", "bound2", "bound3:2"};
  if (o.mutant_searches.empty()) o.mutant_searches = {"random", o.tier == "slow" ? "bound1" : "bound1:2"};
  return o;
}

std::uint64_t random_iterations(const Options& o) { return o.iterations.value_or(o.tier == "slow" ? 1000000 : 100000); }
// A safety net only: with the spin bound every fast-tier search finishes far below it.
std::uint64_t execution_cap(const Options& o) { return o.cap.value_or(o.tier == "slow" ? 100000000 : 10000000); }
std::uint64_t mutant_iterations(const Options& o) {
  return o.mutant_iterations.value_or(o.tier == "slow" ? 100000 : 20000);
}

// "boundN:T" applies only to scenarios with at most T threads.
bool applies(const std::string& search, const ScenarioSpec& scenario) {
  const auto colon = search.find(':');
  return colon == std::string::npos || scenario.threads() <= static_cast<unsigned>(std::stoul(search.substr(colon + 1)));
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

// ---- verdicts -----------------------------------------------------------------------------------------------
struct SearchRecord {
  std::string search;
  SearchResult result;
};

struct VerdictCell {
  std::string policy;
  std::string scenario;
  CheckMode mode;
  Verdict verdict = Verdict::kPass;
  std::string detail;
  std::vector<SearchRecord> searches;
  bool as_expected = true;
  std::string expected;
  std::string history_file;
};

VerdictCell check_cell(const PolicyTable& policy, const ScenarioSpec& scenario, CheckMode mode, const Options& o) {
  VerdictCell cell;
  cell.policy = policy.name;
  cell.scenario = std::string(scenario.name);
  cell.mode = mode;
  const Expectation expect = expected_verdict(policy, scenario, mode);
  for (std::size_t i = 0; i < expect.accepted.size(); ++i) cell.expected += (i ? "|" : "") + std::string(name(expect.accepted[i]));
  current_table() = policy;
  for (const auto& search : o.searches) {
    if (!applies(search, scenario)) continue;
    // Paper's at-least-once check on three threads: its relaxed orders give each load a choice of stores,
    // and the complete bound-1 search of termination ran over 7 minutes without finishing. The fast tier
    // keeps the random search for these cells; the slow tier runs the tree searches.
    if (o.tier == "fast" && mode == CheckMode::kAtLeastOnce && scenario.threads() > 2 && search != "random") continue;
    SearchConfig c = config_for(search, random_iterations(o), o);
    std::string file_name = "history-" + policy.name + "-" + std::string(scenario.name) + ".txt";
    std::replace(file_name.begin(), file_name.end(), ':', '_');
    c.history_path = (std::filesystem::path(o.out) / file_name).string();
    const SearchResult r = run_scenario(scenario, mode, c);
    cell.searches.push_back({search, r});
    if (r.verdict != Verdict::kPass) {
      cell.verdict = r.verdict;
      cell.detail = r.detail;
      cell.history_file = file_name;
      break;  // the first failure decides the cell; its history was written
    }
  }
  if (cell.searches.empty()) {
    // No search of this run applies to the cell (e.g. bound2:2 on a three-thread scenario): it was not
    // checked, so it is neither a pass nor judged against its expectation.
    cell.detail = "not searched (no search of this run applies)";
    cell.as_expected = true;
    return cell;
  }
  cell.as_expected = std::find(expect.accepted.begin(), expect.accepted.end(), cell.verdict) != expect.accepted.end();
  return cell;
}

// ---- mutation -----------------------------------------------------------------------------------------------
struct Kill {
  Mutant mutant;
  bool killed = false;
  std::string by_scenario;
  Verdict verdict = Verdict::kPass;
  std::uint64_t iterations = 0;
  std::string search;
  bool capped = false;  // some search of this mutant stopped at the safety cap (its verdict is not complete)
  std::uint64_t explored = 0;  // executions of every search run against the mutant
  double seconds = 0;
};

std::string mutant_search_text(const Options& o) {
  std::string out;
  for (const auto& s : o.mutant_searches) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// Runs every scenario against one mutant until one kills it: the random search, then the complete bound-1
// search (spin bound; only the safety cap) of the two-thread scenarios (fast tier) or of all (slow tier).
Kill kill_mutant(const Mutant& m, const std::vector<const ScenarioSpec*>& scens, const Options& o) {
  Kill k;
  k.mutant = m;
  current_table() = m.table;
  // Fast tier: the complete bound-1 search on two-thread scenarios (a surviving mutant costs ~75 s when every
  // three-thread scenario gets it too, and a dozen survive as redundant); slow tier: on every scenario.
  for (const std::string& search : o.mutant_searches) {
    for (const ScenarioSpec* s : scens) {
      if (!applies(search, *s)) continue;
      SearchConfig c = config_for(search, mutant_iterations(o), o);
      const SearchResult r = run_scenario(*s, CheckMode::kExactlyOnce, c);
      k.seconds += r.seconds;
      k.explored += r.iterations;
      k.capped = k.capped || r.capped;
      if (r.verdict != Verdict::kPass) {
        k.killed = true;
        k.by_scenario = std::string(s->name);
        k.verdict = r.verdict;
        k.iterations = r.iterations;
        k.capped = r.capped;
        k.search = search;
        return k;
      }
    }
  }
  return k;
}

// Greedy: weaken one site one step at a time, keeping each weakening under which every scenario still passes.
PolicyTable derive_minimal(const PolicyTable& base, const std::vector<const ScenarioSpec*>& scens, const Options& o) {
  PolicyTable t = base;
  bool changed = true;
  while (changed) {
    changed = false;
    for (const Mutant& m : one_step_mutants(t)) {
      const Kill k = kill_mutant(m, scens, o);
      if (!o.quiet) {
        std::fprintf(stderr, "  derive: %-4s %s -> %s: %s\n", std::string(info(m.site).label).c_str(), m.from.c_str(),
                     m.to.c_str(), k.killed ? ("needed (" + k.by_scenario + ")").c_str() : "weakened");
      }
      if (!k.killed) {
        t = m.table;
        changed = true;
        break;
      }
    }
  }
  return t;
}

std::string describe_table(const PolicyTable& t) {
  std::ostringstream out;
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    const Site s = static_cast<Site>(i);
    if (info(s).protocol != Protocol::kStealing) continue;
    out << "  " << info(s).label << " " << info(s).name << ": "
        << (info(s).kind == SiteKind::kFence ? name(t.fences[i]) : name(t.orders[i])) << "\n";
  }
  return out.str();
}

std::string table_cell(const PolicyTable& t, Site s) {
  const std::size_t i = static_cast<std::size_t>(s);
  return std::string(info(s).kind == SiteKind::kFence ? name(t.fences[i]) : name(t.orders[i]));
}

const char* check_name(CheckMode mode) { return mode == CheckMode::kExactlyOnce ? "exactly-once" : "at-least-once"; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One section of the report: its markdown and its part of the JSON document.
struct Section {
  std::string markdown;
  report::Json json;
};

// ---- 1. verdict table ---------------------------------------------------------------------------------------
std::vector<VerdictCell> run_verdicts(const Options& o, const std::vector<const ScenarioSpec*>& scens,
                                      std::chrono::steady_clock::time_point started) {
  std::vector<VerdictCell> cells;
  for (const auto& pname : o.policies) {
    const PolicyTable policy = *policy_by_name(pname);
    std::vector<CheckMode> modes{CheckMode::kExactlyOnce};
    if (policy.contract == Contract::kAtLeastOnce) modes.push_back(CheckMode::kAtLeastOnce);
    for (CheckMode mode : modes) {
      for (const ScenarioSpec* s : scens) {
        VerdictCell c = check_cell(policy, *s, mode, o);
        if (!o.quiet) {
          std::fprintf(stderr, "[%7.1fs] %-20s %-13s %-22s %-10s %s%s\n", seconds_since(started), pname.c_str(),
                       check_name(mode), c.scenario.c_str(),
                       c.searches.empty() ? "not searched" : std::string(name(c.verdict)).c_str(),
                       c.as_expected ? (c.searches.empty() ? "" : "(expected)") : "UNEXPECTED, expected ",
                       c.as_expected ? "" : c.expected.c_str());
        }
        cells.push_back(std::move(c));
      }
    }
  }
  return cells;
}

Section verdict_section(const Options& o, const std::vector<VerdictCell>& cells) {
  report::Table t({{"policy", "policy", false}, {"check", "check", false}, {"scenario", "scenario", false},
                   {"verdict", "verdict", false}, {"expected", "expected", false}, {"searches", "searches", false}});
  for (const VerdictCell& c : cells) {
    std::string shown = (c.searches.empty() ? std::string("—") : std::string(name(c.verdict))) +
                        (c.detail.empty() ? "" : (c.searches.empty() ? " " : ": ") + c.detail) +
                        (c.as_expected ? "" : " **UNEXPECTED**");
    std::string searches_text;
    report::Json searches = report::Json::array();
    for (const auto& sr : c.searches) {
      searches_text += (searches_text.empty() ? "" : "; ") + sr.search + " " + search_summary(sr.result) + " " +
                       report::fixed_text(sr.result.seconds, 2) + " s";
      searches.push_back({{"search", sr.search}, {"verdict", name(sr.result.verdict)}, {"executions", sr.result.iterations},
                          {"completed", sr.result.completed}, {"discarded", sr.result.discarded},
                          {"spin_bound", sr.result.spin_bound}, {"capped", sr.result.capped},
                          {"seconds", sr.result.seconds}});
    }
    t.add_row({c.policy, check_name(c.mode), c.scenario, report::Cell::shown_as(shown, name(c.verdict)), c.expected,
               report::Cell::shown_as(searches_text, searches)});
  }
  Section out;
  out.markdown = "## Verdicts: policy × scenario\n\nEach cell: verdict (as expected?), then per search: executions "
                 "explored and seconds. Expected verdicts are data: models_check/expected_verdicts.hpp.\n\n" +
                 t.markdown() + "\n";
  out.json = t.json();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    out.json[i]["detail"] = cells[i].detail;
    out.json[i]["as_expected"] = cells[i].as_expected;
  }
  // Paper's duplicate, as a readable history.
  for (const VerdictCell& c : cells) {
    if (c.policy == "Paper" && c.verdict == Verdict::kDuplicate && c.scenario == "edge_one_item") {
      out.markdown += "### Paper's duplicate (scenario " + c.scenario + ")\n\nThe failing execution replayed with "
                      "history: `" + c.history_file + "` (next to this file). Read it for the interleaving: the owner's "
                      "store of ListTransient and the thief's store of End both sit unseen while each thread loads the "
                      "other's variable.\n\n";
      std::ifstream h(std::filesystem::path(o.out) / c.history_file);
      std::stringstream text;
      text << h.rdbuf();
      std::printf("\n==== Paper's duplicate found by Relacy (scenario %s): %s ====\n%s\n", c.scenario.c_str(),
                  c.detail.c_str(), text.str().c_str());
    }
  }
  return out;
}

// ---- 2. mutation kill matrix --------------------------------------------------------------------------------
// A survivor is explained either because Minimal orders the site more weakly (the order is redundant), or
// because Fenced's other, stronger orders cover it while Minimal needs it (the certificate kills that weakening
// of Minimal). Anything else would be a missing scenario: `explained` is false.
std::string explain_survivor(const Kill& k, const PolicyTable& base, const std::vector<const ScenarioSpec*>& scens,
                             const Options& o, bool& explained) {
  const PolicyTable minimal = table_of<fs::Minimal>();
  const Site s = k.mutant.site;
  explained = true;
  if (table_cell(minimal, s) != table_cell(base, s)) {
    return "redundant: Minimal orders this site more weakly (" + table_cell(minimal, s) + ")";
  }
  PolicyTable weakened_minimal = minimal;
  if (info(s).kind == SiteKind::kFence) {
    weakened_minimal.fence(s) = k.mutant.table.fences[static_cast<std::size_t>(s)];
  } else {
    weakened_minimal.order(s) = k.mutant.table.orders[static_cast<std::size_t>(s)];
  }
  const Kill in_minimal = kill_mutant(Mutant{s, k.mutant.from, k.mutant.to, weakened_minimal}, scens, o);
  if (in_minimal.killed) {
    return "covered by Fenced's stronger orders elsewhere; needed in Minimal (killed there by " + in_minimal.by_scenario + ")";
  }
  explained = false;
  return "SURVIVOR not explained: a missing scenario";
}

Section kill_matrix_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& all_expected,
                            std::chrono::steady_clock::time_point started) {
  const PolicyTable base = *policy_by_name(o.mutants);
  report::Table t({{"site", "site", false}, {"mutant", "mutant", false}, {"by", "killed by", false},
                   {"verdict", "verdict", false}, {"search", "search", false}, {"executions", "executions"},
                   {"note", "note", false}});
  report::Json details = report::Json::array();
  for (const Mutant& m : one_step_mutants(base)) {
    const Kill k = kill_mutant(m, scens, o);
    const Site s = k.mutant.site;
    bool explained = true;
    const std::string note = k.killed ? "" : explain_survivor(k, base, scens, o, explained);
    all_expected = all_expected && explained;
    if (!o.quiet) {
      std::fprintf(stderr, "[%7.1fs] mutant %-4s %-9s -> %-9s %s\n", seconds_since(started),
                   std::string(info(s).label).c_str(), k.mutant.from.c_str(), k.mutant.to.c_str(),
                   k.killed ? ("killed by " + k.by_scenario + " after " + std::to_string(k.iterations) + " executions").c_str()
                            : note.c_str());
    }
    const std::uint64_t executions = k.killed ? k.iterations : k.explored;
    t.add_row({std::string(info(s).label) + " " + std::string(info(s).name), k.mutant.from + " → " + k.mutant.to,
               k.killed ? k.by_scenario : "—", k.killed ? std::string(name(k.verdict)) : "survived", k.search,
               report::Cell::shown_as(std::to_string(executions) + (k.killed || !k.capped ? "" : " (capped)"), executions),
               note});
    details.push_back({{"site", info(s).label}, {"name", info(s).name}, {"from", k.mutant.from}, {"to", k.mutant.to},
                       {"killed", k.killed}, {"seconds", k.seconds}});
  }
  Section out;
  out.markdown = "## Mutation kill matrix: one-step weakenings of " + base.name + "\n\nEvery labelled site weakened "
                 "one step (seq_cst → acq_rel → acquire/release → relaxed; a fence removed), every scenario run against "
                 "each mutant with the searches " + mutant_search_text(o) + " in that order (random: " +
                 std::to_string(mutant_iterations(o)) + " iterations; boundN: the complete context-bound search of the "
                 "spin-bounded program; boundN:T only on scenarios of at most T threads) until one kills it. "
                 "Executions: until the kill, or all a survivor ran.\n\n" + t.markdown() + "\n";
  report::Json rows = t.json();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (auto it = details[i].begin(); it != details[i].end(); ++it) rows[i][it.key()] = it.value();
  }
  out.json = {{"base", base.name}, {"mutants", rows}};
  return out;
}

// ---- 3. Minimal certificate ---------------------------------------------------------------------------------
Section certificate_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& certified,
                            std::chrono::steady_clock::time_point started) {
  const PolicyTable minimal = table_of<fs::Minimal>();
  report::Table orders({{"site", "site", false}, {"order", "order", false}});
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    const Site s = static_cast<Site>(i);
    if (info(s).protocol != Protocol::kStealing) continue;
    orders.add_row({std::string(info(s).label) + " " + std::string(info(s).name), table_cell(minimal, s)});
  }
  report::Table t({{"site", "site", false}, {"weakening", "weakening", false}, {"by", "killed by", false},
                   {"verdict", "verdict", false}, {"executions", "executions"}});
  const auto mutants = one_step_mutants(minimal);
  certified = true;
  for (const Mutant& m : mutants) {
    const Kill k = kill_mutant(m, scens, o);
    certified = certified && k.killed;
    const Site s = k.mutant.site;
    if (!o.quiet) {
      std::fprintf(stderr, "[%7.1fs] certify %-4s %-9s -> %-9s %s\n", seconds_since(started),
                   std::string(info(s).label).c_str(), k.mutant.from.c_str(), k.mutant.to.c_str(),
                   k.killed ? ("killed by " + k.by_scenario).c_str() : "NOT KILLED: Minimal is not minimal");
    }
    t.add_row({std::string(info(s).label) + " " + std::string(info(s).name), k.mutant.from + " → " + k.mutant.to,
               report::Cell::shown_as(k.killed ? k.by_scenario : "**not killed**", k.by_scenario), name(k.verdict),
               k.iterations});
  }
  Section out;
  out.markdown = "## Certificate of Minimal\n\nMinimal's orders (core/policies.hpp):\n\n" + orders.markdown() +
                 "\nEvery one-step weakening of Minimal, and whether a scenario kills it (all must be killed; that "
                 "Minimal itself passes every scenario is in the verdict table above); searches per weakening, in "
                 "order up to the first kill: " + mutant_search_text(o) + ":\n\n" + t.markdown() + "\n**" +
                 (certified ? "Certified" : "NOT certified") + "**: " + std::to_string(mutants.size()) +
                 " one-step weakenings, " + (certified ? "all" : "not all") + " killed.\n\n";
  out.json = {{"policy", "Minimal"}, {"weakenings", t.json()}, {"certified", certified}};
  return out;
}

std::string preamble(const Options& o) {
  std::string searches;
  for (const auto& s : o.searches) searches += " " + s;
  return "# Model-checking results (Relacy)\n\nTier: " + o.tier + "; random search " +
         std::to_string(random_iterations(o)) + " iterations; searches:" + searches + "; execution depth limit " +
         std::to_string(o.depth) + "; spin bound " + std::to_string(o.spin_bound) + " (frame waits " +
         std::to_string(o.spin_bound + 1) + "); tree searches stop at a safety cap of " +
         std::to_string(execution_cap(o)) + " executions.\n\n"
         "**Bounds.** Relacy keeps a few stores per atomic and never produces load buffering: a pass is a bounded "
         "search, not a proof. The context-bound (and full) searches run each scenario as a finite program: every "
         "wait and idle round may fail at most the spin bound's number of times (one more for frame waits), and an "
         "execution that would fail once more is discarded, its end-of-execution checks skipped "
         "(models_check/relacy_backend.hpp, SPIN BOUND: a failed poll changes nothing, so a longer wait is "
         "equivalent to one in which the other threads ran first). Such a search is exhaustive within its "
         "context bound: per search the report gives executions run to completion and checked (\"done\") "
         "and executions discarded by the spin bound. \"capped\" would mark a search stopped by the safety "
         "cap, i.e. not exhaustive. The bound gives up liveness: a wait that never ends is discarded, not "
         "reported; the random search runs the unbounded program and still reports livelocks, and a tree "
         "search with no complete execution fails as vacuous. A failure is a real execution of the protocol's "
         "own source (histories name core/ files and lines).\n\n";
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  try {
    const report::ResultsDir dir(kProgram, o.out);
    const auto scens = chosen_scenarios(o);
    const auto started = std::chrono::steady_clock::now();
    bool all_expected = true;
    std::string md = preamble(o);
    report::Json js = report::document(kProgram, 2, "model-checked (bounded search)", FRONTSTEAL_GIT_COMMIT);
    js["tool"] = "relacy";
    js["tier"] = o.tier;
    js["random_iterations"] = random_iterations(o);
    if (o.verdicts) {
      const std::vector<VerdictCell> cells = run_verdicts(o, scens, started);
      for (const VerdictCell& c : cells) all_expected = all_expected && c.as_expected;
      const Section v = verdict_section(o, cells);
      md += v.markdown;
      js["verdicts"] = v.json;
    }
    if (!o.mutants.empty()) {
      const Section k = kill_matrix_section(o, scens, all_expected, started);
      md += k.markdown;
      js["kill_matrix"] = k.json;
    }
    if (o.certify) {
      bool certified = true;
      const Section c = certificate_section(o, scens, certified, started);
      md += c.markdown;
      js["certificate"] = c.json;
      all_expected = all_expected && certified;
    }
    if (!o.derive_base.empty()) {
      const PolicyTable derived = derive_minimal(*policy_by_name(o.derive_base), scens, o);
      std::printf("\nDerived from %s (every scenario passes; no single one-step weakening passed):\n%s",
                  o.derive_base.c_str(), describe_table(derived).c_str());
      md += "## Derivation from " + o.derive_base + "\n\n```\n" + describe_table(derived) + "```\n\n";
    }
    md += "Total time: " + report::fixed_text(seconds_since(started), 2) + " s.\n";
    js["seconds"] = seconds_since(started);
    js["all_as_expected"] = all_expected;
    dir.write("modelcheck.md", md);
    dir.write_json("modelcheck.json", js);
    std::printf("\n%s in %.1f s; results: %s, %s\n", all_expected ? "all verdicts as expected" : "UNEXPECTED VERDICTS",
                seconds_since(started), dir.file("modelcheck.md").c_str(), dir.file("modelcheck.json").c_str());
    return all_expected ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
}
