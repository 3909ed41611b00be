// modelcheck_mutation.cpp — frontsteal-modelcheck's kill matrix, certificate of Minimal and derivation.
#include "models_check/modelcheck_mutation.hpp"

#include <cstdio>
#include <sstream>

#include "core/policies.hpp"
#include "models_check/minimal_survivors.hpp"
#include "models_check/report_text.hpp"
#include "reporting/table.hpp"

namespace frontsteal::model::stealing {

namespace {

struct Kill {
  Mutant mutant;
  bool killed = false;
  std::string by_scenario;
  Verdict verdict = Verdict::kPass;
  std::uint64_t iterations = 0;
  std::string search;
  bool capped = false;         // some search of this mutant stopped at the safety cap (its verdict is not complete)
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

std::string table_cell(const PolicyTable& t, Site s) {
  const std::size_t i = static_cast<std::size_t>(s);
  return std::string(info(s).kind == SiteKind::kFence ? name(t.fences[i]) : name(t.orders[i]));
}

// A survivor is explained either because Minimal orders the site more weakly (the order is redundant), or
// because Fenced's other, stronger orders cover it while Minimal needs it (the certificate kills that weakening
// of Minimal). Anything else would be a missing scenario: `explained` is false.
std::string explain_survivor(const Kill& k, const PolicyTable& base, const std::vector<const ScenarioSpec*>& scens,
                             const Options& o, bool& explained) {
  const PolicyTable minimal = table_of<Minimal>();
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
    return "covered by Fenced's stronger orders elsewhere; needed in Minimal (killed there by " +
           in_minimal.by_scenario + ")";
  }
  if (const NeededBeyondRelacy* beyond = find_minimal_survivor(s)) {
    return "needed beyond Relacy's reach (load buffering): killed by the axiomatic checker on the " +
           std::string(beyond->path) + " path under " + std::string(beyond->killed);
  }
  explained = false;
  return "SURVIVOR not explained: a missing scenario";
}

}  // namespace

ReportSection kill_matrix_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& all_expected,
                                  std::chrono::steady_clock::time_point started) {
  const PolicyTable base = *policy_by_name(o.mutants);
  report::Table t({{"site", "site", false},
                   {"mutant", "mutant", false},
                   {"by", "killed by", false},
                   {"verdict", "verdict", false},
                   {"search", "search", false},
                   {"executions", "executions"},
                   {"note", "note", false}});
  report::Json details = report::Json::array();
  for (const Mutant& m : one_step_mutants(base)) {
    const Kill k = kill_mutant(m, scens, o);
    const Site s = k.mutant.site;
    bool explained = true;
    const std::string note = k.killed ? "" : explain_survivor(k, base, scens, o, explained);
    all_expected = all_expected && explained;
    if (!o.quiet) {
      std::fprintf(
          stderr, "[%7.1fs] mutant %-4s %-9s -> %-9s %s\n", seconds_since(started), std::string(info(s).label).c_str(),
          k.mutant.from.c_str(), k.mutant.to.c_str(),
          k.killed ? ("killed by " + k.by_scenario + " after " + std::to_string(k.iterations) + " executions").c_str()
                   : note.c_str());
    }
    const std::uint64_t executions = k.killed ? k.iterations : k.explored;
    t.add_row(
        {site_text(s), k.mutant.from + " → " + k.mutant.to, k.killed ? k.by_scenario : "—",
         k.killed ? std::string(name(k.verdict)) : "survived", k.search,
         report::Cell::shown_as(std::to_string(executions) + (k.killed || !k.capped ? "" : " (capped)"), executions),
         note});
    details.push_back({{"site", info(s).label},
                       {"name", info(s).name},
                       {"from", k.mutant.from},
                       {"to", k.mutant.to},
                       {"killed", k.killed},
                       {"seconds", k.seconds}});
  }
  ReportSection out;
  out.markdown =
      "## Mutation kill matrix: one-step weakenings of " + base.name +
      "\n\nEvery labelled site weakened "
      "one step (seq_cst → acq_rel → acquire/release → relaxed; a fence removed), every scenario run against "
      "each mutant with the searches " +
      mutant_search_text(o) + " in that order (random: " + std::to_string(mutant_iterations(o)) +
      " iterations; boundN: the complete context-bound search of the "
      "spin-bounded program; boundN:T only on scenarios of at most T threads) until one kills it. "
      "Executions: until the kill, or all a survivor ran.\n\n" +
      t.markdown() + "\n";
  report::Json rows = t.json();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (auto it = details[i].begin(); it != details[i].end(); ++it) rows[i][it.key()] = it.value();
  }
  out.json = {{"base", base.name}, {"mutants", rows}};
  return out;
}

ReportSection certificate_section(const Options& o, const std::vector<const ScenarioSpec*>& scens, bool& certified,
                                  std::chrono::steady_clock::time_point started) {
  const PolicyTable minimal = table_of<Minimal>();
  report::Table orders({{"site", "site", false}, {"order", "order", false}});
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    const Site s = static_cast<Site>(i);
    if (info(s).protocol != Protocol::kStealing) continue;
    orders.add_row({site_text(s), table_cell(minimal, s)});
  }
  report::Table t({{"site", "site", false},
                   {"weakening", "weakening", false},
                   {"by", "killed by", false},
                   {"verdict", "verdict", false},
                   {"executions", "executions"}});
  const auto mutants = one_step_mutants(minimal);
  certified = true;
  int beyond_relacy = 0;
  for (const Mutant& m : mutants) {
    const Kill k = kill_mutant(m, scens, o);
    const Site s = k.mutant.site;
    // A listed survivor counts as killed by the axiomatic checker; a listed one that Relacy kills means the
    // list no longer follows the evidence.
    const NeededBeyondRelacy* listed = find_minimal_survivor(s);
    const bool beyond = listed != nullptr && !k.killed;
    beyond_relacy += beyond ? 1 : 0;
    const bool ok = listed == nullptr ? k.killed : beyond;
    certified = certified && ok;
    const std::string by = k.killed ? k.by_scenario
                           : beyond ? "axiomatic checker: " + std::string(listed->path) + " under " +
                                          std::string(listed->killed) + " (survives Relacy: no load buffering)"
                                    : "**not killed**";
    const std::string shown = ok ? by : (listed ? "**killed by " + k.by_scenario + ", listed as a survivor**" : by);
    if (!o.quiet) {
      std::fprintf(stderr, "[%7.1fs] certify %-4s %-9s -> %-9s %s\n", seconds_since(started),
                   std::string(info(s).label).c_str(), k.mutant.from.c_str(), k.mutant.to.c_str(),
                   ok ? ("killed by " + by).c_str()
                      : (listed ? "KILLED BY RELACY, but listed in minimal_survivors.hpp: the list is stale"
                                : "NOT KILLED: Minimal is not minimal"));
    }
    t.add_row({site_text(s), k.mutant.from + " → " + k.mutant.to, report::Cell::shown_as(shown, by),
               beyond ? std::string(name(Verdict::kEarlyQuit)) + " (axiomatic)" : std::string(name(k.verdict)),
               beyond ? k.explored : k.iterations});  // a survivor: every Relacy execution it passed
  }
  ReportSection out;
  out.markdown = "## Certificate of Minimal\n\nMinimal's orders (core/policies.hpp):\n\n" + orders.markdown() +
                 "\nEvery one-step weakening of Minimal, and whether a scenario kills it (all must be killed; that "
                 "Minimal itself passes every scenario is in the verdict table above); searches per weakening, in "
                 "order up to the first kill: " +
                 mutant_search_text(o) + ":\n\n" + t.markdown() + "\n**" + (certified ? "Certified" : "NOT certified") +
                 "**: " + std::to_string(mutants.size()) + " one-step weakenings, " + (certified ? "all" : "not all") +
                 " killed (" + std::to_string(beyond_relacy) +
                 " by the axiomatic checker under load buffering, which Relacy cannot produce: "
                 "models_check/minimal_survivors.hpp).\n\n";
  out.json = {{"policy", "Minimal"}, {"weakenings", t.json()}, {"certified", certified}};
  return out;
}

// Greedy: weaken one site one step at a time, keeping each weakening under which every scenario still passes.
PolicyTable derive_minimal(const PolicyTable& base, const std::vector<const ScenarioSpec*>& scens, const Options& o) {
  PolicyTable t = base;
  bool changed = true;
  while (changed) {
    changed = false;
    for (const Mutant& m : one_step_mutants(t)) {
      // A site needed beyond Relacy's reach keeps its order: Relacy would let the weakening through.
      const NeededBeyondRelacy* beyond = find_minimal_survivor(m.site);
      if (beyond != nullptr && t.orders[static_cast<std::size_t>(m.site)] == beyond->order) continue;
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

}  // namespace frontsteal::model::stealing
