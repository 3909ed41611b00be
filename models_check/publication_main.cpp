// frontsteal-modelcheck-publication — model-check greedy rendering's triangle publication and reclamation
// (core/component_publication.hpp) with Relacy: verdicts of the sound policy and of two planted defects on every
// publication scenario, and the kill matrix of every one-step weakening of the sound policy's orders.
//
// This file never includes Relacy (publication_suite.cpp does).
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/cli_args.hpp"
#include "core/publication_policies.hpp"
#include "models_check/report_text.hpp"
#include "models_check/publication_check.hpp"
#include "models_check/table_policy.hpp"

using namespace frontsteal;
using namespace frontsteal::model;

namespace {

constexpr std::string_view kProgram = "frontsteal-modelcheck-publication";

constexpr std::string_view kUsage = R"(usage: frontsteal-modelcheck-publication [options]

Model-checks greedy rendering's publication of per-component triangles and the reclamation of the buffers the
pusher may still draw (core/component_publication.hpp) with Relacy. Checks: no torn component, no use of a slot
after its reuse (a data race on the triangles), no component going back in time, the last frame published at
the end, no deadlock. Runs the sound policy (Publication) and two planted defects (Broken:ReuseWithoutGrace,
Broken:PublishEachSurface: both must fail) on every scenario of models_check/publication_scenarios.hpp, then
weakens each publication site of Publication by one step (all must be killed). Writes markdown and JSON; exits 1
on any unexpected verdict.

options:
  --iterations N         random-search iterations per policy and scenario               (default 100000)
  --mutant-iterations N  random-search iterations per mutant and scenario                (default 20000)
  --bound N              also a context-bound search with this bound, 0: none                  (default 3)
  --full                 also the full search (every interleaving within the spin bound)
  --mutant-bound N       context-bound search for each mutant after its random search, 0: none (default 1)
  --cap N                safety net: a tree search that explores more executions than this is
                         reported as capped, and a capped search fails the run       (default 10000000)
  --no-mutants           skip the kill matrix
  --out DIR              results directory                          (default out/modelcheck-publication)
  --quiet                no progress lines
  --help                 this text

Bounds, stated honestly: the tree searches (context-bound, full) run each wait of the program at most one
failed iteration (frame-long waits two) and discard the executions that would wait longer (spin-assume,
models_check/relacy_backend.hpp); within that and their context bound they are complete, and the report gives
the executions explored to completion per cell. Relacy keeps a few stores per atomic and never produces load
buffering; the random search is a sample. A pass is a complete bounded search, not a proof.
)";

struct Options {
  std::uint64_t iterations = 100000;
  std::uint64_t mutant_iterations = 20000;
  unsigned bound = 3;
  bool full = false;
  unsigned mutant_bound = 1;
  std::uint64_t cap = 10'000'000;
  bool mutants = true;
  std::string out = "out/modelcheck-publication";
  bool quiet = false;
};

Options parse(int argc, char** argv) {
  Options o;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  const auto count = [&](std::string_view flag, std::string_view v) {
    return cli::parse_number<std::uint64_t>(kProgram, flag, v, 1, 1'000'000'000);
  };
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--iterations") {
      o.iterations = count(a, args.value());
    } else if (a == "--mutant-iterations") {
      o.mutant_iterations = count(a, args.value());
    } else if (a == "--bound") {
      o.bound = cli::parse_number<unsigned>(kProgram, a, args.value(), 0, 4);
    } else if (a == "--full") {
      o.full = true;
    } else if (a == "--mutant-bound") {
      o.mutant_bound = cli::parse_number<unsigned>(kProgram, a, args.value(), 0, 4);
    } else if (a == "--cap") {
      o.cap = count(a, args.value());
    } else if (a == "--no-mutants") {
      o.mutants = false;
    } else if (a == "--out") {
      o.out = args.value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      cli::usage_error(kProgram, "unknown option '" + std::string(a) + "'");
    }
  }
  return o;
}

// One search of one table on one scenario, as run.
struct Cell {
  std::string scenario;
  SearchResult result;
};

// Every search of one table over every scenario (random, then the tree searches), up to the first failure.
struct Outcome {
  std::string scenario;  // where it failed (empty: passed everywhere)
  SearchResult result;
  std::uint64_t executions = 0;
  std::vector<Cell> cells;
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

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::filesystem::create_directories(o.out + "/histories");
  const auto start = std::chrono::steady_clock::now();
  std::ostringstream md, js;
  bool ok = true;
  md << "# Publication and reclamation: Relacy verdicts (measured)\n\n"
     << "core/component_publication.hpp under Relacy; " << o.iterations << " random iterations"
     << (o.bound > 0 ? ", then the complete context-bound search (bound " + std::to_string(o.bound) + ")"
                     : std::string())
     << (o.full ? ", then the complete full search" : "")
     << " per policy and scenario; tree searches under the spin bound (each wait fails at most once, frame-long "
        "waits twice; longer executions are discarded, models_check/relacy_backend.hpp). Scenarios (models_check/publication_scenarios.hpp):\n\n";
  for (const PublicationSpec& s : publication_scenarios()) md << "- `" << s.name << "`: " << s.checks << "\n";
  md << "\n## Verdicts\n\n| policy | expected | verdict | executions explored (random + tree, discarded included) |\n|---|---|---|---|\n";
  js << "{\n  \"verdicts\": [\n";

  struct Row {
    PolicyTable table;
    bool must_pass;
  };
  const std::vector<Row> rows{{table_of<PublicationOrders>(), true},
                              {table_of<BrokenReuseWithoutGrace>(), false},
                              {table_of<BrokenPublishEachSurface>(), false}};
  std::vector<Cell> sound_cells;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Row& row = rows[k];
    if (!o.quiet) std::cerr << kProgram << ": " << row.table.name << " …\n";
    const Outcome out = check_table(row.table, o.iterations, o.bound, o.full, o.cap, o.out + "/histories");
    if (row.must_pass) sound_cells = out.cells;
    const bool passed = out.scenario.empty();
    const bool as_expected = passed == row.must_pass;
    ok = ok && as_expected;
    if (!o.quiet) std::cerr << "  " << describe(out) << (as_expected ? "" : "  UNEXPECTED") << "\n";
    md << "| " << row.table.name << " | " << (row.must_pass ? "pass" : "fail (negative control)") << " | "
       << describe(out) << (as_expected ? "" : " **UNEXPECTED**") << " | " << out.executions << " |\n";
    js << "    {\"policy\": \"" << row.table.name << "\", \"expected_pass\": " << (row.must_pass ? "true" : "false")
       << ", \"verdict\": \"" << json_escape(describe(out)) << "\", \"as_expected\": " << (as_expected ? "true" : "false")
       << ", \"executions\": " << out.executions << "}" << (k + 1 < rows.size() ? "," : "") << "\n";
  }
  md << "\n## Every search of Publication (executions explored to completion, time)\n\n"
     << "| scenario | search | executions | seconds | verdict |\n|---|---|---|---|---|\n";
  js << "  ],\n  \"searches\": [\n";
  for (std::size_t k = 0; k < sound_cells.size(); ++k) {
    const Cell& c = sound_cells[k];
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.2f", c.result.seconds);
    const std::string search(name(c.result.kind));
    md << "| " << c.scenario << " | " << search
       << (c.result.kind == SearchKind::kContextBound ? " " + std::to_string(c.result.bound) : std::string()) << " | "
       << search_summary(c.result) << " | " << secs << " | " << name(c.result.verdict) << " |\n";
    js << "    {\"scenario\": \"" << c.scenario << "\", \"search\": \"" << search << "\", \"bound\": " << c.result.bound
       << ", \"iterations\": " << c.result.iterations << ", \"completed\": " << c.result.completed
       << ", \"discarded\": " << c.result.discarded << ", \"capped\": " << (c.result.capped ? "true" : "false")
       << ", \"seconds\": " << c.result.seconds << ", \"verdict\": \"" << name(c.result.verdict) << "\"}"
       << (k + 1 < sound_cells.size() ? "," : "") << "\n";
  }
  js << "  ],\n  \"mutants\": [\n";

  if (o.mutants) {
    const auto mutants = one_step_mutants(table_of<PublicationOrders>(), Protocol::kPublication);
    md << "\n## Kill matrix: every one-step weakening of Publication (all must be killed)\n\n"
       << o.mutant_iterations << " random iterations, then "
       << (o.mutant_bound > 0 ? "the complete context-bound search (bound " + std::to_string(o.mutant_bound) + ")"
                              : std::string("no tree search"))
       << " per scenario, up to the first failure.\n\n"
       << "| site | order | weakened to | killed by | executions |\n|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < mutants.size(); ++k) {
      const Mutant& m = mutants[k];
      if (!o.quiet) std::cerr << kProgram << ": mutant " << (k + 1) << "/" << mutants.size() << " " << m.table.name << "\n";
      const Outcome out = check_table(m.table, o.mutant_iterations, o.mutant_bound, false, o.cap, "");
      const bool killed = !out.scenario.empty();
      ok = ok && killed;
      md << "| " << info(m.site).label << " " << info(m.site).name << " | " << m.from << " | " << m.to << " | "
         << (killed ? describe(out) : "**survived**") << " | " << out.executions << " |\n";
      js << "    {\"site\": \"" << info(m.site).label << "\", \"from\": \"" << m.from << "\", \"to\": \"" << m.to
         << "\", \"killed\": " << (killed ? "true" : "false") << ", \"by\": \"" << json_escape(describe(out))
         << "\", \"executions\": " << out.executions << "}" << (k + 1 < mutants.size() ? "," : "") << "\n";
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  js << "  ],\n  \"all_as_expected\": " << (ok ? "true" : "false") << ",\n  \"seconds\": " << seconds << "\n}\n";
  md << "\n" << (ok ? "Every verdict as expected." : "**Some verdicts were not as expected.**") << " Run time "
     << static_cast<int>(seconds) << " s. Failing executions' histories: histories/.\n";
  std::ofstream(o.out + "/publication.md") << md.str();
  std::ofstream(o.out + "/publication.json") << js.str();
  std::cout << md.str();
  if (!o.quiet) std::cerr << kProgram << ": wrote " << o.out << "/publication.{md,json}\n";
  return ok ? 0 : 1;
}
