// frontsteal-modelcheck-graph — core/'s own source under RC11 and ARMv8, by execution-graph exploration
// (explorer.hpp): the policy × model × scenario table, each cell a verdict with its execution counts, judged
// against the expected verdicts.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "models_check/checker_report.hpp"
#include "models_check/expected_verdicts.hpp"
#include "models_check/graph/stealing_program.hpp"
#include "reporting/command_line.hpp"

using namespace frontsteal;
using namespace frontsteal::model;
namespace graph = frontsteal::graph;

namespace {

constexpr const char* kProgram = "frontsteal-modelcheck-graph";
constexpr const char* kDescription =
    R"(Model-checks core/'s own stealing protocol and frame loop by execution-graph exploration (GenMC/TruSt
style, models_check/graph/explorer.hpp): every scenario of models_check/scenarios.hpp under every chosen
policy and memory model, each consistent execution explored once. Writes graph-verdicts.md and .json; exits
1 when a verdict differs from the expected one, 2 for bad usage.)";
constexpr const char* kFooter = R"(
Models: rc11 (C++, RC11 with no-thin-air), armv8 (the standard mapping, acquire -> LDAR), armv8-ldapr
(acquire -> LDAPR). What is explored: executions whose po ∪ rf is acyclic, no dependency assumed between a read
and a later access; waits by spin-assume; at most --steals steal linearizations (T3) per execution, runs past
the bound are cut and counted. Load buffering is the litmus tier's (frontsteal-litmus).)";

struct Options {
  std::vector<std::string> policies{"all"}, scenarios{"owner_vs_thief"}, models{"all"};
  std::string mode = "exactly-once";
  int steals = 1;
  double max_seconds = 900;
  std::string mutants;  // a policy whose one-step weakenings to run (a kill matrix), or empty
  std::string out = "graph-results";
  bool quiet = false;
  bool no_maximality = false;
};

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> policy_names{"all"}, scenario_names{"all"};
  for (const auto& p : known_stealing_policies()) policy_names.push_back(p.name);
  for (const auto& s : scenarios()) scenario_names.emplace_back(s.name);
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.app()
      .add_option("--policy", o.policies, "comma-separated policy names, or all")
      ->delimiter(',')
      ->check(CLI::IsMember(policy_names).description(""));
  cli.app()
      .add_option("--scenario", o.scenarios, "comma-separated scenario names, or all")
      ->delimiter(',')
      ->check(CLI::IsMember(scenario_names).description(""));
  cli.app()
      .add_option("--model", o.models, "comma-separated: rc11, armv8, armv8-ldapr, or all")
      ->delimiter(',')
      ->check(CLI::IsMember({"all", "rc11", "armv8", "armv8-ldapr"}).description(""));
  cli.option("--mode", o.mode, "exactly-once or at-least-once")
      ->check(CLI::IsMember({"exactly-once", "at-least-once"}));
  cli.option("--steals", o.steals, "steal linearizations (T3) allowed per execution; past it a run is cut")
      ->check(CLI::Range(1, 4));
  cli.option("--max-seconds", o.max_seconds, "per cell; a cell stopped by it is marked bounded (not exhaustive)")
      ->check(CLI::PositiveNumber);
  cli.option("--mutants", o.mutants,
             "also run every one-step weakening of this policy's stealing sites on the chosen scenarios and models "
             "(a kill matrix; reported, not judged)")
      ->check(CLI::IsMember(policy_names).description(""));
  cli.flag("--no-maximality", o.no_maximality,
           "take every backward revisit (no TruSt maximality condition): executions repeat and the search is "
           "slower; for cross-checking the explorer's distinct counts, not for verdicts");
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  return o;
}

std::vector<graph::GraphModel> chosen_models(const Options& o) {
  std::vector<graph::GraphModel> out;
  for (const auto& m : o.models) {
    if (m == "all" || m == "rc11") out.push_back(graph::GraphModel::rc11);
    if (m == "all" || m == "armv8") out.push_back(graph::GraphModel::armv8_ldar);
    if (m == "all" || m == "armv8-ldapr") out.push_back(graph::GraphModel::armv8_ldapr);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// One cell's exploration: the model, the steal bound, the time limit, and the maximality condition unless turned off.
graph::ExploreOptions explore_options(const Options& o, graph::GraphModel m) {
  graph::ExploreOptions eo;
  eo.model = m;
  eo.bound = o.steals;
  eo.max_seconds = o.max_seconds;
  if (o.no_maximality) eo.defect = graph::ExplorerDefect::no_maximality;
  return eo;
}

// The Relacy tier's expectations (expected_verdicts.hpp) hold under RC11 and ARMv8 with LDAPR; with LDAR, Paper's
// handshake is ordered by the store-release → load-acquire rule (bob's [L];po;[A]) and it is exactly-once
// (docs/model-checking.md's policy × model table).
Expectation expected(const PolicyTable& p, const ScenarioSpec& s, CheckMode mode, graph::GraphModel m) {
  if (m == graph::GraphModel::armv8_ldar && p.name == "Paper") {
    return {{Verdict::kPass}, "LDAR after STLR: the handshake's store→load order holds"};
  }
  return expected_verdict(p, s, mode);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  return run_checker(kProgram, [&] {
    CheckerReport results(kProgram, o.out, /*histories=*/false);
    const CheckMode mode = o.mode == "exactly-once" ? CheckMode::kExactlyOnce : CheckMode::kAtLeastOnce;
    results.markdown =
        "# Execution-graph model checking of core/ (" + o.mode +
        " check)\n\nEach cell runs core/frame_loop.hpp and core/stealing_protocol.hpp themselves over the "
        "execution-graph backend and explores every consistent execution once (models_check/graph/explorer.hpp): "
        "executions with po ∪ rf acyclic, no dependency assumed, waits by spin-assume, at most " +
        std::to_string(o.steals) +
        " steal linearization(s) (T3) per execution (runs past it are cut). \"complete\": executions run to the end "
        "and checked; \"distinct\": of those, different graphs (equal: nothing explored twice); \"blocked\": runs "
        "ending in a wait a newer write satisfies in another branch; \"cut\": runs past the steal bound.\n\n"
        "| scenario | policy | model | verdict | expected | complete | distinct | blocked | cut | revisits | "
        "largest graph | seconds |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    results.json["tool"] = "execution-graph explorer";
    results.json["mode"] = o.mode;
    results.json["steal_bound"] = o.steals;
    report::Json cells = report::Json::array();
    bool all_expected = true;
    std::string failures;
    for (const ScenarioSpec& s : scenarios()) {
      if (std::find(o.scenarios.begin(), o.scenarios.end(), "all") == o.scenarios.end() &&
          std::find(o.scenarios.begin(), o.scenarios.end(), s.name) == o.scenarios.end()) {
        continue;
      }
      for (const PolicyTable& p : known_stealing_policies()) {
        if (std::find(o.policies.begin(), o.policies.end(), "all") == o.policies.end() &&
            std::find(o.policies.begin(), o.policies.end(), p.name) == o.policies.end()) {
          continue;
        }
        for (graph::GraphModel m : chosen_models(o)) {
          current_table() = p;
          graph::StealingProgram program(s, mode);
          graph::ExploreOptions eo = explore_options(o, m);
          if (!o.quiet) {
            eo.progress = [&, next = 10.0](std::uint64_t runs, std::uint64_t complete, std::size_t pending,
                                           double seconds) mutable {
              if (seconds < next) return;
              next += 10;
              std::cerr << "  " << s.name << " / " << p.name << " / " << graph::name(m) << ": " << runs << " runs, "
                        << complete << " complete executions, " << pending << " branches pending, "
                        << static_cast<int>(seconds) << " s\n";
            };
          }
          const graph::ExploreResult r = graph::explore(program, eo);
          const Expectation want = expected(p, s, mode, m);
          const bool as_expected =
              std::find(want.accepted.begin(), want.accepted.end(), r.outcome.verdict) != want.accepted.end() &&
              !(r.outcome.verdict == Verdict::kPass && (r.bounded || r.complete == 0)) &&
              (r.complete == r.distinct || o.no_maximality);  // a repeat is the explorer's defect, not a verdict
          all_expected = all_expected && as_expected;
          std::string accepted;
          for (Verdict v : want.accepted) accepted += (accepted.empty() ? "" : " or ") + std::string(name(v));
          char line[512];
          std::snprintf(line, sizeof line,
                        "| %s | %s | %s | %s%s | %s | %llu | %llu | %llu | %llu | %llu | %zu | %.1f |\n",
                        std::string(s.name).c_str(), p.name.c_str(), std::string(graph::name(m)).c_str(),
                        std::string(name(r.outcome.verdict)).c_str(),
                        r.bounded                  ? ", **incomplete** (stopped by --max-seconds)"
                        : r.complete != r.distinct ? " **REPEATED EXECUTIONS** (explorer defect)"
                        : as_expected              ? ""
                                                   : " **UNEXPECTED**",
                        accepted.c_str(), static_cast<unsigned long long>(r.complete),
                        static_cast<unsigned long long>(r.distinct), static_cast<unsigned long long>(r.blocked),
                        static_cast<unsigned long long>(r.cut), static_cast<unsigned long long>(r.revisits),
                        r.largest_graph, r.seconds);
          results.markdown += line;
          if (!o.quiet) std::cerr << line;
          if (r.outcome.verdict != Verdict::kPass) {
            failures += "### " + std::string(s.name) + " / " + p.name + " / " + std::string(graph::name(m)) + ": " +
                        std::string(name(r.outcome.verdict)) + "\n\n" + r.outcome.detail + "\n\n```\n" + r.witness +
                        "```\n\n";
          }
          cells.push_back({{"scenario", s.name},
                           {"policy", p.name},
                           {"model", graph::name(m)},
                           {"verdict", name(r.outcome.verdict)},
                           {"detail", r.outcome.detail},
                           {"as_expected", as_expected},
                           {"complete", r.complete},
                           {"distinct", r.distinct},
                           {"blocked", r.blocked},
                           {"hangs", r.hangs},
                           {"cut", r.cut},
                           {"ended_early", r.ended_early},
                           {"revisits", r.revisits},
                           {"revisits_repeated", r.revisits_repeated},
                           {"revisits_not_maximal", r.revisits_not_maximal},
                           {"largest_graph", r.largest_graph},
                           {"bounded", r.bounded},
                           {"seconds", r.seconds}});
        }
      }
    }
    results.json["cells"] = cells;
    if (!o.mutants.empty()) {
      results.markdown +=
          "\n## Kill matrix: one-step weakenings of " + o.mutants +
          "\n\nEach mutant weakens one site of the policy by one step (models_check/table_policy.hpp); a "
          "cell is the verdict of the first chosen scenario that fails, or pass.\n\n| mutant |";
      const auto models = chosen_models(o);
      for (graph::GraphModel m : models) results.markdown += " " + std::string(graph::name(m)) + " |";
      results.markdown += "\n|---|";
      for (std::size_t i = 0; i < models.size(); ++i) results.markdown += "---|";
      results.markdown += "\n";
      report::Json matrix = report::Json::array();
      PolicyTable base;
      for (const PolicyTable& p : known_stealing_policies()) {
        if (p.name == o.mutants) base = p;
      }
      for (const Mutant& mutant : one_step_mutants(base)) {
        results.markdown += "| " + mutant.table.name + " |";
        for (graph::GraphModel m : models) {
          Verdict verdict = Verdict::kPass;
          std::string where;
          bool incomplete = false;
          for (const ScenarioSpec& s : scenarios()) {
            if (verdict != Verdict::kPass) break;
            if (std::find(o.scenarios.begin(), o.scenarios.end(), "all") == o.scenarios.end() &&
                std::find(o.scenarios.begin(), o.scenarios.end(), s.name) == o.scenarios.end()) {
              continue;
            }
            current_table() = mutant.table;
            graph::StealingProgram program(s, mode);
            const graph::ExploreResult r = graph::explore(program, explore_options(o, m));
            verdict = r.outcome.verdict;
            where = std::string(s.name);
            incomplete = incomplete || r.bounded;
          }
          results.markdown += " " + std::string(name(verdict)) +
                              (verdict != Verdict::kPass ? " (" + where + ")"
                               : incomplete              ? " (incomplete: stopped by --max-seconds)"
                                                         : "") +
                              " |";
          matrix.push_back({{"mutant", mutant.table.name},
                            {"model", graph::name(m)},
                            {"verdict", name(verdict)},
                            {"incomplete", incomplete},
                            {"scenario", where}});
          if (!o.quiet) std::cerr << mutant.table.name << " under " << graph::name(m) << ": " << name(verdict) << "\n";
        }
        results.markdown += "\n";
      }
      results.json["kill_matrix"] = matrix;
    }
    if (!failures.empty()) {
      // Every counterexample in a file of its own (they run to hundreds of kilobytes); the first one here.
      results.dir().write("graph-counterexamples.md",
                          "# Counterexamples (events per thread with their site labels "
                          "and core/ lines; rf; co)\n\n" +
                              failures);
      results.markdown +=
          "\n## The first counterexample (every one: graph-counterexamples.md)\n\n" +
          failures.substr(
              0, failures.find("\n### ", 4) == std::string::npos ? failures.size() : failures.find("\n### ", 4) + 1);
    }
    return results.close("graph-verdicts", all_expected, o.quiet);
  });
}
