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

#include "core/cli_args.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "models_check/report_text.hpp"
#include "models_check/expected_verdicts.hpp"
#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"

namespace fs = frontsteal;
using namespace frontsteal;
using namespace frontsteal::model;

namespace {

constexpr std::string_view kProgram = "frontsteal-modelcheck";

[[noreturn]] void usage_error(const std::string& m) { cli::usage_error(kProgram, m); }

using cli::split_list;

constexpr std::string_view kUsage = R"(usage: frontsteal-modelcheck [options]

Model-checks the load-stealing protocol of core/ with Relacy: every scenario of models_check/scenarios.hpp
under every chosen policy, with random and context-bound searches; optionally a memory-order mutation kill
matrix and the certificate of the Minimal policy. Writes markdown and JSON results; exits 1 on any verdict
that differs from the expected-verdict table (models_check/expected_verdicts.hpp).

options:
  --tier fast|slow       fast: 1e5 random iterations, complete context bound 1, bound 2 for 2-thread scenarios,
                         2e4 random iterations per mutant, then complete bound 1 on 2-thread scenarios
                         slow: 1e6 random iterations, bounds 1 and 2, bound 3 for 2-thread scenarios, 1e5
                         per mutant                                                           (default fast)
  --policy LIST          comma-separated: SeqCst,Paper,Fenced,Asymmetric,Minimal,Broken:SkipsReread,
                         Broken:NoTransient,Broken:JoinsLate,Broken:ShareLowerBound, or all (default all)
  --scenario LIST        comma-separated scenario names, or all                               (default all)
  --search LIST          comma-separated: random,bound1,bound2,bound3,full; boundN:T only for scenarios of at
                         most T threads                                     (default random,bound1,bound2:2)
  --iterations N         random-search iterations (overrides the tier)
  --cap N                safety cap: executions after which a context-bound or full search stops (overrides
                         the tier: fast 1e7, slow 1e8); results say "capped" when a search stopped there
  --mutants POLICY       also run the kill matrix of every one-step weakening of POLICY
  --mutant-iterations N  random-search iterations per mutant and scenario (overrides the tier)
  --mutant-search LIST   searches run against each mutant, in order, up to the first kill (same names as
                         --search)                       (default: fast random,bound1:2; slow random,bound1)
  --certify              also certify Minimal: every one-step weakening must be killed
  --derive-minimal BASE  greedily weaken BASE while every scenario passes; print the resulting table
  --no-verdicts          skip the policy x scenario verdict table
  --spin-bound K         tree searches: failed iterations allowed per wait or idle round before the execution
                         is discarded (0: unbounded, the searches then hit the cap)                (default 1)
  --depth N              Relacy execution_depth_limit                                        (default 20000)
  --out DIR              results directory                                      (default out/modelcheck)
  --quiet                no progress lines
  --help                 this text

Bounds, stated honestly: Relacy keeps a few stores per atomic and never produces load buffering. Context-bound
searches run the finite program of the spin bound (each wait may fail --spin-bound times, frame waits once
more; longer waits are discarded and counted) and are exhaustive within their bound unless "capped"; the
random search runs the unbounded program. A pass is a bounded search, not a proof.
)";

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

std::uint64_t parse_count(std::string_view flag, std::string_view text) {
  const auto v = cli::parse_number<std::uint64_t>(kProgram, flag, text, 0, std::numeric_limits<std::uint64_t>::max());
  if (v == 0) usage_error(std::string(flag) + " must be at least 1");
  return v;
}

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

Options parse(int argc, char** argv) {
  Options o;
  std::string policies = "all";
  std::string scenario_list = "all";
  bool searches_given = false;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    auto value = [&] { return args.value(); };
    if (a == "--tier") {
      o.tier = value();
      if (o.tier != "fast" && o.tier != "slow") usage_error("--tier is fast or slow, got '" + o.tier + "'");
    } else if (a == "--policy") {
      policies = value();
    } else if (a == "--scenario") {
      scenario_list = value();
    } else if (a == "--search") {
      o.searches = split_list(value());
      searches_given = true;
    } else if (a == "--iterations") {
      o.iterations = parse_count(a, value());
    } else if (a == "--cap") {
      o.cap = parse_count(a, value());
    } else if (a == "--mutants") {
      o.mutants = value();
    } else if (a == "--mutant-search") {
      o.mutant_searches = split_list(value());
    } else if (a == "--mutant-iterations") {
      o.mutant_iterations = parse_count(a, value());
    } else if (a == "--certify") {
      o.certify = true;
    } else if (a == "--derive-minimal") {
      o.derive_base = value();
    } else if (a == "--no-verdicts") {
      o.verdicts = false;
    } else if (a == "--spin-bound") {
      o.spin_bound = cli::parse_number<unsigned>(kProgram, a, value(), 0, 16);
    } else if (a == "--depth") {
      o.depth = static_cast<unsigned>(parse_count(a, value()));
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      usage_error("unknown option '" + std::string(a) + "'");
    }
  }
  for (const auto& name : policies == "all" ? std::vector<std::string>{} : split_list(policies)) {
    if (!policy_by_name(name)) usage_error("unknown policy '" + name + "'");
    o.policies.push_back(name);
  }
  if (policies == "all") {
    for (const auto& p : known_policies()) o.policies.push_back(p.name);
  }
  if (o.tier == "slow" && !searches_given) o.searches = {"random", "bound1", "bound2", "bound3:2"};
  if (o.mutant_searches.empty()) {
    o.mutant_searches = {"random", o.tier == "slow" ? "bound1" : "bound1:2"};
  }
  std::vector<std::string> all_searches = o.searches;
  all_searches.insert(all_searches.end(), o.mutant_searches.begin(), o.mutant_searches.end());
  for (const auto& s : all_searches) {
    const std::string base = s.substr(0, s.find(':'));
    if (base != "random" && base != "bound1" && base != "bound2" && base != "bound3" && base != "full") {
      usage_error("unknown search '" + s + "' (random, bound1, bound2, bound3, full; boundN:T for at most T threads)");
    }
  }
  if (scenario_list != "all") {
    for (const auto& name : split_list(scenario_list)) {
      const auto& all = scenarios();
      if (std::none_of(all.begin(), all.end(), [&](const ScenarioSpec& s) { return s.name == name; })) {
        usage_error("unknown scenario '" + name + "'");
      }
      o.scenarios.push_back(name);
    }
  }
  if (!o.mutants.empty() && !policy_by_name(o.mutants)) usage_error("unknown policy for --mutants: '" + o.mutants + "'");
  if (!o.derive_base.empty() && !policy_by_name(o.derive_base)) {
    usage_error("unknown policy for --derive-minimal: '" + o.derive_base + "'");
  }
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

std::string fmt_seconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f", s);
  return b;
}

// ---- verdicts -----------------------------------------------------------------------------------------------
struct SearchRecord {
  std::string search;
  SearchResult result;
};

struct Cell {
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

Cell check_cell(const PolicyTable& policy, const ScenarioSpec& scenario, CheckMode mode, const Options& o) {
  Cell cell;
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

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) {
    std::cerr << "frontsteal-modelcheck: cannot create " << o.out << ": " << ec.message() << "\n";
    return 1;
  }
  const auto scens = chosen_scenarios(o);
  const auto started = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
  bool all_expected = true;

  std::ostringstream md;
  std::ostringstream js;
  md << "# Model-checking results (Relacy)\n\n"
     << "Tier: " << o.tier << "; random search " << random_iterations(o) << " iterations; searches:";
  for (const auto& s : o.searches) md << " " << s;
  md << "; execution depth limit " << o.depth
     << "; spin bound " << o.spin_bound << " (frame waits " << o.spin_bound + 1 << ")"
     << "; tree searches stop at a safety cap of " << execution_cap(o) << " executions.\n\n"
     << "**Bounds.** Relacy keeps a few stores per atomic and never produces load buffering: a pass is a bounded "
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
  js << "{\n  \"tool\": \"relacy\", \"kind\": \"model-checked (bounded search)\", \"tier\": \"" << o.tier
     << "\", \"random_iterations\": " << random_iterations(o) << ",\n";

  // ---- 1. verdict table ------------------------------------------------------------------------------------
  std::vector<Cell> cells;
  if (o.verdicts) {
    for (const auto& pname : o.policies) {
      const PolicyTable policy = *policy_by_name(pname);
      std::vector<CheckMode> modes{CheckMode::kExactlyOnce};
      if (policy.contract == Contract::kAtLeastOnce) modes.push_back(CheckMode::kAtLeastOnce);
      for (CheckMode mode : modes) {
        for (const ScenarioSpec* s : scens) {
          Cell c = check_cell(policy, *s, mode, o);
          if (!o.quiet) {
            std::fprintf(stderr, "[%7.1fs] %-20s %-13s %-22s %-10s %s%s\n", elapsed(), pname.c_str(),
                         mode == CheckMode::kExactlyOnce ? "exactly-once" : "at-least-once", c.scenario.c_str(),
                         c.searches.empty() ? "not searched" : std::string(name(c.verdict)).c_str(),
                         c.as_expected ? (c.searches.empty() ? "" : "(expected)") : "UNEXPECTED, expected ",
                         c.as_expected ? "" : c.expected.c_str());
          }
          all_expected = all_expected && c.as_expected;
          cells.push_back(std::move(c));
        }
      }
    }
    md << "## Verdicts: policy × scenario\n\n"
       << "Each cell: verdict (as expected?), then per search: executions explored and seconds. "
          "Expected verdicts are data: models_check/expected_verdicts.hpp.\n\n"
       << "| policy | check | scenario | verdict | expected | searches |\n|---|---|---|---|---|---|\n";
    js << "  \"verdicts\": [\n";
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const Cell& c = cells[i];
      md << "| " << c.policy << " | " << (c.mode == CheckMode::kExactlyOnce ? "exactly-once" : "at-least-once") << " | "
         << c.scenario << " | " << (c.searches.empty() ? std::string("—") : std::string(name(c.verdict)))
         << (c.detail.empty() ? "" : (c.searches.empty() ? " " : ": ") + c.detail)
         << (c.as_expected ? "" : " **UNEXPECTED**") << " | " << c.expected << " | ";
      js << "    {\"policy\": \"" << c.policy << "\", \"check\": \""
         << (c.mode == CheckMode::kExactlyOnce ? "exactly-once" : "at-least-once") << "\", \"scenario\": \""
         << c.scenario << "\", \"verdict\": \"" << name(c.verdict) << "\", \"detail\": \"" << json_escape(c.detail)
         << "\", \"expected\": \"" << c.expected << "\", \"as_expected\": " << (c.as_expected ? "true" : "false")
         << ", \"searches\": [";
      for (std::size_t j = 0; j < c.searches.size(); ++j) {
        const auto& sr = c.searches[j];
        md << (j ? "; " : "") << sr.search << " " << search_summary(sr.result) << " " << fmt_seconds(sr.result.seconds) << " s";
        js << (j ? ", " : "") << "{\"search\": \"" << sr.search << "\", \"verdict\": \"" << name(sr.result.verdict)
           << "\", \"executions\": " << sr.result.iterations << ", \"completed\": " << sr.result.completed
           << ", \"discarded\": " << sr.result.discarded << ", \"spin_bound\": " << sr.result.spin_bound
           << ", \"capped\": " << (sr.result.capped ? "true" : "false") << ", \"seconds\": " << sr.result.seconds << "}";
      }
      md << " |\n";
      js << "]}" << (i + 1 < cells.size() ? "," : "") << "\n";
    }
    js << "  ],\n";
    md << "\n";
    // Paper's duplicate, as a readable history.
    for (const Cell& c : cells) {
      if (c.policy == "Paper" && c.verdict == Verdict::kDuplicate && c.scenario == "edge_one_item") {
        md << "### Paper's duplicate (scenario " << c.scenario << ")\n\n"
           << "The failing execution replayed with history: `" << c.history_file
           << "` (next to this file). Read it for the interleaving: the owner's store of ListTransient and the "
              "thief's store of End both sit unseen while each thread loads the other's variable.\n\n";
        std::ifstream h(std::filesystem::path(o.out) / c.history_file);
        std::stringstream text;
        text << h.rdbuf();
        std::printf("\n==== Paper's duplicate found by Relacy (scenario %s): %s ====\n%s\n", c.scenario.c_str(),
                    c.detail.c_str(), text.str().c_str());
      }
    }
  }

  // ---- 2. mutation kill matrix -----------------------------------------------------------------------------
  std::vector<Kill> kills;
  if (!o.mutants.empty()) {
    const PolicyTable base = *policy_by_name(o.mutants);
    const PolicyTable minimal = table_of<fs::Minimal>();
    md << "## Mutation kill matrix: one-step weakenings of " << base.name << "\n\n"
       << "Every labelled site weakened one step (seq_cst → acq_rel → acquire/release → relaxed; a fence "
          "removed), every scenario run against each mutant with the searches "
       << mutant_search_text(o)
       << " in that order (random: " << mutant_iterations(o)
       << " iterations; boundN: the complete context-bound search of the spin-bounded program; boundN:T only on "
          "scenarios of at most T threads) until one kills it. Executions: until the kill, or all a survivor "
          "ran.\n\n"
       << "| site | mutant | killed by | verdict | search | executions | note |\n|---|---|---|---|---|---|---|\n";
    js << "  \"kill_matrix\": {\"base\": \"" << base.name << "\", \"mutants\": [\n";
    const auto mutants = one_step_mutants(base);
    for (std::size_t i = 0; i < mutants.size(); ++i) {
      Kill k = kill_mutant(mutants[i], scens, o);
      const Site s = k.mutant.site;
      const bool minimal_drops = table_cell(minimal, s) != table_cell(base, s);
      std::string note;
      if (!k.killed) {
        // A survivor is explained either because Minimal orders the site more weakly (the order is redundant),
        // or because Fenced's other, stronger orders cover it while Minimal needs it (the certificate kills
        // that weakening of Minimal). Anything else would be a missing scenario.
        if (minimal_drops) {
          note = "redundant: Minimal orders this site more weakly (" + table_cell(minimal, s) + ")";
        } else {
          PolicyTable weakened_minimal = minimal;
          if (info(s).kind == SiteKind::kFence) {
            weakened_minimal.fence(s) = k.mutant.table.fences[static_cast<std::size_t>(s)];
          } else {
            weakened_minimal.order(s) = k.mutant.table.orders[static_cast<std::size_t>(s)];
          }
          const Kill in_minimal = kill_mutant(Mutant{s, k.mutant.from, k.mutant.to, weakened_minimal}, scens, o);
          if (in_minimal.killed) {
            note = "covered by Fenced's stronger orders elsewhere; needed in Minimal (killed there by " +
                   in_minimal.by_scenario + ")";
          } else {
            note = "SURVIVOR not explained: a missing scenario";
            all_expected = false;
          }
        }
      }
      if (!o.quiet) {
        std::fprintf(stderr, "[%7.1fs] mutant %-4s %-9s -> %-9s %s\n", elapsed(), std::string(info(s).label).c_str(),
                     k.mutant.from.c_str(), k.mutant.to.c_str(),
                     k.killed ? ("killed by " + k.by_scenario + " after " + std::to_string(k.iterations) + " executions").c_str()
                              : note.c_str());
      }
      md << "| " << info(s).label << " " << info(s).name << " | " << k.mutant.from << " → " << k.mutant.to << " | "
         << (k.killed ? k.by_scenario : "—") << " | " << (k.killed ? name(k.verdict) : "survived") << " | "
         << (k.killed ? k.search : "") << " | " << (k.killed ? std::to_string(k.iterations) : std::to_string(k.explored) + (k.capped ? " (capped)" : "")) << " | " << note
         << " |\n";
      js << "    {\"site\": \"" << info(s).label << "\", \"name\": \"" << info(s).name << "\", \"from\": \""
         << k.mutant.from << "\", \"to\": \"" << k.mutant.to << "\", \"killed\": " << (k.killed ? "true" : "false")
         << ", \"by\": \"" << k.by_scenario << "\", \"verdict\": \"" << name(k.verdict) << "\", \"search\": \""
         << k.search << "\", \"executions\": " << k.iterations << ", \"seconds\": " << k.seconds << ", \"note\": \""
         << json_escape(note) << "\"}" << (i + 1 < mutants.size() ? "," : "") << "\n";
      kills.push_back(std::move(k));
    }
    js << "  ]},\n";
    md << "\n";
  }

  // ---- 3. Minimal certificate ------------------------------------------------------------------------------
  if (o.certify) {
    const PolicyTable minimal = table_of<fs::Minimal>();
    md << "## Certificate of Minimal\n\nMinimal's orders (core/policies.hpp):\n\n| site | order |\n|---|---|\n";
    for (std::size_t i = 0; i < kSiteCount; ++i) {
      const Site s = static_cast<Site>(i);
      if (info(s).protocol != Protocol::kStealing) continue;
      md << "| " << info(s).label << " " << info(s).name << " | " << table_cell(minimal, s) << " |\n";
    }
    md << "\nEvery one-step weakening of Minimal, and whether a scenario kills it (all must be killed; that "
          "Minimal itself passes every scenario is in the verdict table above); searches per weakening, in "
          "order up to the first kill: "
       << mutant_search_text(o) << ":\n\n"
       << "| site | weakening | killed by | verdict | executions |\n|---|---|---|---|---|\n";
    js << "  \"certificate\": {\"policy\": \"Minimal\", \"weakenings\": [\n";
    const auto mutants = one_step_mutants(minimal);
    bool certified = true;
    for (std::size_t i = 0; i < mutants.size(); ++i) {
      const Kill k = kill_mutant(mutants[i], scens, o);
      certified = certified && k.killed;
      const Site s = k.mutant.site;
      if (!o.quiet) {
        std::fprintf(stderr, "[%7.1fs] certify %-4s %-9s -> %-9s %s\n", elapsed(), std::string(info(s).label).c_str(),
                     k.mutant.from.c_str(), k.mutant.to.c_str(),
                     k.killed ? ("killed by " + k.by_scenario).c_str() : "NOT KILLED: Minimal is not minimal");
      }
      md << "| " << info(s).label << " " << info(s).name << " | " << k.mutant.from << " → " << k.mutant.to << " | "
         << (k.killed ? k.by_scenario : "**not killed**") << " | " << name(k.verdict) << " | " << k.iterations << " |\n";
      js << "    {\"site\": \"" << info(s).label << "\", \"from\": \"" << k.mutant.from << "\", \"to\": \"" << k.mutant.to
         << "\", \"killed\": " << (k.killed ? "true" : "false") << ", \"by\": \"" << k.by_scenario
         << "\", \"executions\": " << k.iterations << "}" << (i + 1 < mutants.size() ? "," : "") << "\n";
    }
    js << "  ], \"certified\": " << (certified ? "true" : "false") << "},\n";
    md << "\n**" << (certified ? "Certified" : "NOT certified") << "**: " << mutants.size()
       << " one-step weakenings, " << (certified ? "all" : "not all") << " killed.\n\n";
    all_expected = all_expected && certified;
  }

  // ---- 4. derivation ---------------------------------------------------------------------------------------
  if (!o.derive_base.empty()) {
    const PolicyTable derived = derive_minimal(*policy_by_name(o.derive_base), scens, o);
    std::printf("\nDerived from %s (every scenario passes; no single one-step weakening passed):\n%s",
                o.derive_base.c_str(), describe_table(derived).c_str());
    md << "## Derivation from " << o.derive_base << "\n\n```\n" << describe_table(derived) << "```\n\n";
  }

  md << "Total time: " << fmt_seconds(elapsed()) << " s.\n";
  js << "  \"seconds\": " << elapsed() << ", \"all_as_expected\": " << (all_expected ? "true" : "false") << "\n}\n";
  const auto md_path = std::filesystem::path(o.out) / "modelcheck.md";
  const auto js_path = std::filesystem::path(o.out) / "modelcheck.json";
  std::ofstream(md_path) << md.str();
  std::ofstream(js_path) << js.str();
  std::printf("\n%s in %.1f s; results: %s, %s\n", all_expected ? "all verdicts as expected" : "UNEXPECTED VERDICTS",
              elapsed(), md_path.c_str(), js_path.c_str());
  return all_expected ? 0 : 1;
}
