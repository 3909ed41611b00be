// chaselev_verdicts.cpp — the Chase–Lev checker's verdict table and kill matrix.
#include "models_check/chaselev_verdicts.hpp"

#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/chase_lev_policies.hpp"
#include "models_check/chaselev_check.hpp"
#include "models_check/chaselev_survivors.hpp"
#include "models_check/report_text.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::model::chaselev {

namespace {

std::string seconds_text(double s) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(s < 10 ? 2 : 1) << s;
  return o.str();
}

// One search of one scenario: pass only if it found nothing and, for a tree search, was not capped.
struct SearchCell {
  SearchKind kind;
  SearchResult result;
  bool passed() const { return result.verdict == Verdict::kPass && !result.capped; }
  std::string describe() const {
    if (result.verdict == Verdict::kPass) return result.capped ? "incomplete (capped)" : "pass";
    const std::string v(name(result.verdict));
    return result.detail.empty() ? v : v + ": " + result.detail;
  }
  // Executions: a random search's iterations; a tree search's executions run to the end (or to the failure).
  std::uint64_t executions() const {
    return kind == SearchKind::kRandom ? result.iterations : (passed() ? result.completed : result.iterations);
  }
};

SearchCell run_cell(const ChaseLevSpec& spec, SearchKind kind, std::uint64_t iterations, unsigned bound,
                    std::uint64_t cap, const std::string& history_path) {
  SearchConfig config;
  config.kind = kind;
  config.iterations = iterations;
  config.bound = bound;
  config.execution_cap = cap;
  config.history_path = history_path;
  return SearchCell{kind, run_chaselev(spec, config)};
}

std::string file_safe(std::string s) {
  for (char& c : s) {
    if (c == ':' || c == '[' || c == ']' || c == '/') c = '_';
  }
  return s;
}

// Every search of one scenario under current_table(), as budget asks.
std::vector<SearchCell> search_scenario(const ChaseLevSpec& spec, const SearchBudget& o, const std::string& hist) {
  std::vector<SearchCell> cells{run_cell(spec, SearchKind::kRandom, o.iterations, 0, 0, hist + "-random.txt")};
  if (o.bound > 0) cells.push_back(run_cell(spec, SearchKind::kContextBound, 0, o.bound, o.cap, hist + "-bound.txt"));
  if (o.full) cells.push_back(run_cell(spec, SearchKind::kFull, 0, 0, o.cap, hist + "-full.txt"));
  return cells;
}

void print_cells(const ChaseLevSpec& spec, const std::vector<SearchCell>& cells) {
  std::cerr << "  " << spec.name;
  for (const SearchCell& c : cells) {
    std::cerr << "  [" << name(c.kind) << ": " << c.describe() << ", " << c.executions() << " executions, "
              << seconds_text(c.result.seconds) << " s]";
  }
  std::cerr << "\n";
}

}  // namespace

report::Table verdict_table(const SearchBudget& o, bool& ok) {
  struct Row {
    PolicyTable table;
    bool must_pass;
  };
  const std::vector<Row> rows{{table_of<ChaseLevOrders>(), true},
                              {table_of<BrokenTakeWithoutFence>(), false},
                              {table_of<BrokenTakeLastWithoutCas>(), false},
                              {table_of<BrokenPushWithoutRelease>(), false}};
  report::Table t({{"policy", "policy", false},
                   {"expected_pass", "expected", false},
                   {"scenario", "scenario", false},
                   {"search", "search", false},
                   {"verdict", "verdict", false},
                   {"executions", "executions"},
                   {"seconds", "s"}});
  for (const Row& row : rows) {
    progress(kProgram, o.quiet, row.table.name + " …");
    current_table() = row.table;
    bool row_passed = true;
    const report::Cell expected = expectation_cell(row.must_pass);
    for (const ChaseLevSpec& spec : chaselev_scenarios()) {
      const std::string hist = o.out + "/histories/" + file_safe(row.table.name) + "-" + std::string(spec.name);
      const std::vector<SearchCell> cells = search_scenario(spec, o, hist);
      bool scenario_passed = true;
      for (const SearchCell& c : cells) scenario_passed = scenario_passed && c.passed();
      row_passed = row_passed && scenario_passed;
      if (row.must_pass && !scenario_passed) ok = false;
      if (!o.quiet) print_cells(spec, cells);
      for (const SearchCell& c : cells) {
        const std::string search =
            std::string(name(c.kind)) +
            (c.kind == SearchKind::kContextBound ? " (bound " + std::to_string(o.bound) + ")" : std::string());
        t.add_row({row.table.name, expected, report::Cell::shown_as("`" + std::string(spec.name) + "`", spec.name),
                   search,
                   report::Cell::shown_as(
                       c.describe(), {{"verdict", c.describe()}, {"passed", c.passed()}, {"capped", c.result.capped}}),
                   c.executions(), report::Cell::shown_as(seconds_text(c.result.seconds), c.result.seconds)});
      }
    }
    if (row_passed != row.must_pass) {
      ok = false;
      t.add_row(
          {row.table.name,
           report::Cell::shown_as(std::string("**UNEXPECTED**: ") + (row_passed ? "passed" : "failed"), "unexpected"),
           report::Cell::empty(), report::Cell::empty(), report::Cell::empty(), report::Cell::empty(),
           report::Cell::empty()});
    }
  }
  return t;
}

report::Table kill_table(const SearchBudget& o, bool& ok) {
  report::Table t(weakening_columns({{"verdict", "killed by", false}, {"executions", "executions"}, {"seconds", "s"}}));
  const auto mutants = one_step_mutants(table_of<ChaseLevOrders>(), Protocol::kChaseLev);
  std::vector<SearchKind> kinds{SearchKind::kRandom};
  if (o.bound > 0) kinds.push_back(SearchKind::kContextBound);
  for (std::size_t k = 0; k < mutants.size(); ++k) {
    const Mutant& m = mutants[k];
    mutant_progress(kProgram, o.quiet, k, mutants.size(), m.table.name);
    current_table() = m.table;
    std::string killed_by;
    std::uint64_t executions = 0;
    double seconds = 0;
    bool incomplete = false;
    for (SearchKind kind : kinds) {
      for (const ChaseLevSpec& spec : chaselev_scenarios()) {
        const SearchCell c = run_cell(spec, kind, o.mutant_iterations, o.bound, o.cap, "");
        executions += c.executions();
        seconds += c.result.seconds;
        incomplete = incomplete || c.result.capped;
        if (c.result.verdict != Verdict::kPass) {
          killed_by = c.describe() + ", in " + std::string(spec.name) + " (" + std::string(name(kind)) + ")";
          break;
        }
      }
      if (!killed_by.empty()) break;
    }
    const bool killed = !killed_by.empty();
    const ExpectedSurvivor* listed = find_survivor(m.table.name);
    const bool as_expected = killed ? listed == nullptr : (listed != nullptr && !incomplete);
    ok = ok && as_expected;
    std::string verdict = killed ? killed_by
                                 : std::string("**survived**") + (incomplete ? " (a search was capped)" : "") +
                                       (listed ? ": " + std::string(listed->why) : std::string(" — not listed"));
    if (!as_expected) verdict += " **UNEXPECTED**";
    if (!o.quiet) std::cerr << "  " << verdict << "\n";
    t.add_row({site_text(m.site), m.from, m.to,
               report::Cell::shown_as(verdict, {{"killed", killed}, {"by", verdict}, {"as_expected", as_expected}}),
               executions, report::Cell::shown_as(seconds_text(seconds), seconds)});
  }
  return t;
}

}  // namespace frontsteal::model::chaselev
