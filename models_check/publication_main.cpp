// frontsteal-modelcheck-publication — model-check greedy rendering's triangle publication and reclamation
// (core/component_publication.hpp) with Relacy: verdicts of the sound policy and of two planted defects on every
// publication scenario, and the kill matrix of every one-step weakening of the sound policy's orders.
//
// The report's frame (results directory, JSON header, closing line) is checker_report.hpp's, the shared options
// checker_options.hpp's. This file never includes Relacy (publication_suite.cpp does).
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/publication_policies.hpp"
#include "models_check/checker_options.hpp"
#include "models_check/checker_report.hpp"
#include "models_check/publication_check.hpp"
#include "models_check/report_text.hpp"
#include "models_check/table_policy.hpp"
#include "reporting/table.hpp"

using namespace frontsteal;
using namespace frontsteal::model;
namespace report = frontsteal::report;

namespace {

constexpr const char* kProgram = "frontsteal-modelcheck-publication";
constexpr const char* kDescription =
    R"(Model-checks greedy rendering's publication of per-component triangles and the reclamation of the buffers the
pusher may still draw (core/component_publication.hpp) with Relacy. Checks: no torn component, no use of a slot
after its reuse (a data race on the triangles), no component going back in time, the last frame published at
the end, no deadlock. Runs the sound policy (Publication) and two planted defects (Broken:ReuseWithoutGrace,
Broken:PublishEachSurface: both must fail) on every scenario of models_check/publication_scenarios.hpp, then
weakens each publication site of Publication by one step (all must be killed). Writes markdown and JSON; exits 1
on any unexpected verdict, 2 for bad usage.)";
constexpr const char* kFooter = R"(
Bounds, stated honestly: the tree searches (context-bound, full) run each wait of the program at most one
failed iteration (frame-long waits two) and discard the executions that would wait longer (spin-assume,
models_check/relacy_backend.hpp); within that and their context bound they are complete, and the report gives
the executions explored to completion per cell. Relacy keeps a few stores per atomic and never produces load
buffering; the random search is a sample. A pass is a complete bounded search, not a proof.)";

struct Options : SearchBudget {
  unsigned mutant_bound = 1;
};

Options parse(int argc, char** argv) {
  Options o;
  o.bound = 3;
  o.cap = 10'000'000;
  o.out = "out/modelcheck-publication";
  CheckerCommandLine cli(kProgram, kDescription, kFooter, o, "also a context-bound search with this bound, 0: none");
  cli.full("also the full search (every interleaving within the spin bound)");
  cli.cli()
      .option("--mutant-bound", o.mutant_bound, "context-bound search for each mutant after its random search, 0: none")
      ->check(CLI::Range(0u, 4u));
  cli.cap(
      "safety net: a tree search that explores more executions than this is reported as capped, and a capped "
      "search fails the run");
  cli.parse(argc, argv);
  return o;
}

// One search of one table on one scenario, as run.
struct SearchCell {
  std::string scenario;
  SearchResult result;
};

// Every search of one table over every scenario (random, then the tree searches), up to the first failure.
struct Outcome {
  std::string scenario;  // where it failed (empty: passed everywhere)
  SearchResult result;
  std::uint64_t executions = 0;
  std::vector<SearchCell> cells;
};

Outcome check_table(const PolicyTable& table, std::uint64_t iterations, unsigned bound, bool full, std::uint64_t cap,
                    const std::string& history_dir) {
  current_table() = table;
  Outcome o;
  for (const PublicationSpec& spec : publication_scenarios()) {
    std::vector<SearchConfig> searches(1);
    searches[0].kind = SearchKind::kRandom;
    searches[0].iterations = iterations;
    if (bound > 0) {
      SearchConfig bounded;
      bounded.kind = SearchKind::kContextBound;
      bounded.bound = bound;
      bounded.execution_cap = cap;
      searches.push_back(bounded);
    }
    if (full) {
      SearchConfig complete;
      complete.kind = SearchKind::kFull;
      complete.execution_cap = cap;
      searches.push_back(complete);
    }
    for (SearchConfig config : searches) {
      if (!history_dir.empty()) config.history_path = history_dir + "/" + std::string(spec.name) + ".txt";
      const SearchResult r = run_publication(spec, config);
      o.executions += r.iterations;
      o.cells.push_back({std::string(spec.name), r});
      if (r.verdict != Verdict::kPass) {
        o.scenario = spec.name;
        o.result = r;
        return o;
      }
      if (r.capped) {  // a capped tree search is a sample, not a pass: say so by failing the table
        o.scenario = spec.name;
        o.result = r;
        o.result.verdict = Verdict::kOtherFailure;
        o.result.detail = "tree search capped at " + std::to_string(cap) + " executions (not complete)";
        return o;
      }
    }
  }
  return o;
}

std::string describe(const Outcome& o) {
  if (o.scenario.empty()) return "pass";
  const std::string verdict(name(o.result.verdict));
  return (o.result.detail.empty() ? verdict : verdict + ": " + o.result.detail) + ", in " + o.scenario;
}

struct Row {
  PolicyTable table;
  bool must_pass;
};

// The sound policy and the two planted defects, every scenario; `sound_cells` gets every search of the sound one.
report::Table verdict_table(const Options& o, bool& ok, std::vector<SearchCell>& sound_cells) {
  const std::vector<Row> rows{{table_of<PublicationOrders>(), true},
                              {table_of<BrokenReuseWithoutGrace>(), false},
                              {table_of<BrokenPublishEachSurface>(), false}};
  report::Table t({{"policy", "policy", false},
                   {"expected_pass", "expected", false},
                   {"verdict", "verdict", false},
                   {"executions", "executions explored (random + tree, discarded included)"}});
  for (const Row& row : rows) {
    progress(kProgram, o.quiet, row.table.name + " …");
    const Outcome out = check_table(row.table, o.iterations, o.bound, o.full, o.cap, o.out + "/histories");
    if (row.must_pass) sound_cells = out.cells;
    const bool as_expected = out.scenario.empty() == row.must_pass;
    ok = ok && as_expected;
    if (!o.quiet) std::cerr << "  " << describe(out) << (as_expected ? "" : "  UNEXPECTED") << "\n";
    t.add_row({row.table.name, expectation_cell(row.must_pass),
               report::Cell::shown_as(describe(out) + (as_expected ? "" : " **UNEXPECTED**"), describe(out)),
               out.executions});
  }
  return t;
}

report::Table search_table(const std::vector<SearchCell>& cells) {
  report::Table t({{"scenario", "scenario", false},
                   {"search", "search", false},
                   {"executions", "executions", false},
                   {"seconds", "seconds"},
                   {"verdict", "verdict", false}});
  for (const SearchCell& c : cells) {
    const std::string search(name(c.result.kind));
    t.add_row(
        {c.scenario,
         search + (c.result.kind == SearchKind::kContextBound ? " " + std::to_string(c.result.bound) : std::string()),
         report::Cell::shown_as(search_summary(c.result), {{"iterations", c.result.iterations},
                                                           {"completed", c.result.completed},
                                                           {"discarded", c.result.discarded},
                                                           {"capped", c.result.capped}}),
         report::Cell::fixed(c.result.seconds, 2), name(c.result.verdict)});
  }
  return t;
}

report::Table kill_table(const Options& o, bool& ok) {
  report::Table t(weakening_columns({{"by", "killed by", false}, {"executions", "executions"}}));
  const auto mutants = one_step_mutants(table_of<PublicationOrders>(), Protocol::kPublication);
  for (std::size_t k = 0; k < mutants.size(); ++k) {
    const Mutant& m = mutants[k];
    mutant_progress(kProgram, o.quiet, k, mutants.size(), m.table.name);
    const Outcome out = check_table(m.table, o.mutant_iterations, o.mutant_bound, false, o.cap, "");
    const bool killed = !out.scenario.empty();
    ok = ok && killed;
    t.add_row({site_text(m.site), m.from, m.to,
               report::Cell::shown_as(killed ? describe(out) : "**survived**",
                                      killed ? report::Json(describe(out)) : nullptr),
               out.executions});
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  return run_checker(kProgram, [&] {
    CheckerReport results(kProgram, o.out, /*histories=*/true);
    bool ok = true;
    std::ostringstream md;
    md << "# Publication and reclamation: Relacy verdicts (measured)\n\n"
       << "core/component_publication.hpp under Relacy; " << o.iterations << " random iterations"
       << (o.bound > 0 ? ", then the complete context-bound search (bound " + std::to_string(o.bound) + ")"
                       : std::string())
       << (o.full ? ", then the complete full search" : "")
       << " per policy and scenario; tree searches under the spin bound (each wait fails at most once, frame-long "
          "waits twice; longer executions are discarded, models_check/relacy_backend.hpp). Scenarios "
          "(models_check/publication_scenarios.hpp):\n\n";
    for (const PublicationSpec& s : publication_scenarios()) md << "- `" << s.name << "`: " << s.checks << "\n";
    std::vector<SearchCell> sound_cells;
    const report::Table verdicts = verdict_table(o, ok, sound_cells);
    const report::Table searches = search_table(sound_cells);
    md << "\n## Verdicts\n\n"
       << verdicts.markdown() << "\n## Every search of Publication (executions explored to completion, time)\n\n"
       << searches.markdown();
    results.json["verdicts"] = verdicts.json();
    results.json["searches"] = searches.json();
    results.json["mutants"] = report::Json::array();
    if (o.mutants) {
      const report::Table kills = kill_table(o, ok);
      md << "\n## Kill matrix: every one-step weakening of Publication (all must be killed)\n\n"
         << o.mutant_iterations << " random iterations, then "
         << (o.mutant_bound > 0 ? "the complete context-bound search (bound " + std::to_string(o.mutant_bound) + ")"
                                : std::string("no tree search"))
         << " per scenario, up to the first failure.\n\n"
         << kills.markdown();
      results.json["mutants"] = kills.json();
    }
    results.markdown = md.str();
    return results.close("publication", ok, o.quiet);
  });
}
