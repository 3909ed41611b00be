// stress_report.cpp — frontsteal-stress's tables and results files.
#include "stress/stress_report.hpp"

#include <sstream>
#include <thread>

#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"

namespace frontsteal::stress {

namespace {

report::Table race_table(const std::vector<RaceRow>& races, const Options& o) {
  report::Table t({{"policy", "policy", false},
                   {"rounds", "rounds"},
                   {"items_per_round", "items per round"},
                   {"steals_kept", "steals kept"},
                   {"skipped", "items skipped after re-read"},
                   {"duplicates", "duplicates"},
                   {"rounds_with_duplicates", "rounds with duplicates"},
                   {"duplicates_per_million_rounds", "duplicates per 1e6 rounds"},
                   {"seconds", "seconds"}});
  for (const auto& row : races) {
    const auto& x = row.result;
    t.add_row({row.policy, x.rounds, o.race_items, x.steals_kept, x.skipped, x.duplicates, x.rounds_with_duplicates,
               report::Cell::fixed(x.duplicates_per_million_rounds(), 2), report::Cell::fixed(x.seconds, 1)});
  }
  return t;
}

report::Table case_table(const std::vector<CaseResult>& cases) {
  report::Table t({{"target", "target", false},
                   {"contract", "contract", false},
                   {"threads", "P"},
                   {"frames", "frames"},
                   {"seconds", "seconds"},
                   {"frames_with_0_duplicates", "0 dup"},
                   {"frames_with_1_duplicate", "1 dup"},
                   {"frames_with_2plus_duplicates", "2+ dup"},
                   {"lost", "lost"},
                   {"duplicated", "duplicated"},
                   {"duplicates_per_million_items", "dup per 1e6 items"},
                   {"steals", "steals"},
                   {"skipped", "skipped"},
                   {"chaos_injections", "chaos"},
                   {"negative_control", "control", false},
                   {"passed", "passed", false},
                   {"verdict", "verdict", false}});
  for (const auto& c : cases) {
    t.add_row({c.target, c.contract, c.threads, c.frames, report::Cell::fixed(c.seconds, 3), c.frames_dup0,
               c.frames_dup1, c.frames_dup2plus, c.lost, c.duplicated,
               report::Cell::fixed(c.duplicates_per_million_items(), 3), c.steals, c.skipped, c.chaos,
               c.negative_control, c.passed, c.verdict});
  }
  return t;
}

report::Table scenario_table(const std::vector<ScenarioRow>& rows) {
  report::Table t({{"target", "target", false},
                   {"scenario", "scenario", false},
                   {"runs", "runs"},
                   {"lost", "lost"},
                   {"duplicated", "duplicated"},
                   {"passed", "result", false}});
  for (const auto& r : rows) {
    t.add_row({r.target, r.scenario, r.runs, r.lost, r.duplicated,
               report::Cell::shown_as(r.passed ? "as expected" : "**FAIL**", r.passed)});
  }
  return t;
}

report::Table fault_table(const std::vector<FaultResult>& faults) {
  report::Table t({{"fault", "fault", false}, {"passed", "result", false}, {"detail", "detail", false}});
  for (const auto& f : faults)
    t.add_row({f.name, report::Cell::shown_as(f.passed ? "pass" : "**FAIL**", f.passed), f.detail});
  return t;
}

}  // namespace

void write_results(const Options& o, const StressReport& r, double seconds) {
#if defined(__SANITIZE_THREAD__)
  const char* build = "ThreadSanitizer";
#else
  const char* build = "release (no sanitizer)";
#endif
  const report::ResultsDir dir(kProgram, o.out);
  std::ostringstream md;
  md << "# " << (o.rates ? "Duplicate rates on real hardware" : "Stress results") << " (measured)\n\n";
  if (!r.races.empty()) {
    md << "## The handshake raced head-on\n\nEach round the owner claims a list of " << o.race_items << " items ("
       << o.race_work << " multiply-adds after each) while the thief makes one steal attempt on it at the same moment "
       << "(stress/handshake_race.hpp); a duplicate is an id the owner claimed and the thief kept.\n\n"
       << race_table(r.races, o).markdown() << "\n## Frame level\n\n";
  }
  md << "Build: " << build << "; " << std::thread::hardware_concurrency() << " hardware threads; items per frame "
     << o.items << "; chaos " << (o.rates ? 0 : o.chaos) << " per million labelled accesses; seed " << o.seed << "; "
     << (o.frames ? std::to_string(o.frames) + " frames" : report::fixed_text(o.seconds, 1) + " s")
     << " per case; a negative control runs until it is caught (at most " << report::fixed_text(o.control_seconds, 0)
     << " s), so its frames and seconds are the time to the first duplicate.\n\n"
     << case_table(r.cases).markdown();
  if (!r.scenario_rows.empty()) {
    md << "\n## The model checker's scenarios on real threads\n\nThe configurations of models_check/scenarios.hpp, "
          "each "
       << "run " << o.scenario_runs << " times per target (for the negative controls a duplicate here is a catch, but "
       << "not required: the frame-level cases above must catch them).\n\n"
       << scenario_table(r.scenario_rows).markdown();
  }
  if (!r.faults.empty()) md << "\n## Faults\n\n" << fault_table(r.faults).markdown();
  md << "\n"
     << (r.all_ok ? "All cases as expected" : "**Some cases failed**") << "; total " << report::fixed_text(seconds, 1)
     << " s.\n";
  dir.write(o.rates ? "rates.md" : "stress.md", md.str());

  report::Json js = report::document(kProgram, 2, "measured", FRONTSTEAL_GIT_COMMIT);
  js["build"] = build;
  js["items"] = o.items;
  js["chaos_per_million"] = o.rates ? 0 : o.chaos;
  js["handshake_race"] = race_table(r.races, o).json();
  js["cases"] = case_table(r.cases).json();
  js["scenarios"] = scenario_table(r.scenario_rows).json();
  js["faults"] = fault_table(r.faults).json();
  js["all_passed"] = r.all_ok;
  js["seconds"] = seconds;
  dir.write_json(o.rates ? "rates.json" : "stress.json", js);
}

}  // namespace frontsteal::stress
