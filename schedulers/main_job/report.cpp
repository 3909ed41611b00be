// report.cpp — the main job's reporting (report.hpp): the heading and the table on stdout,
// frontsteal.md, and the closing lines; the analysis, the tables, the JSON and the plots come from their own
// files (analysis.hpp, tables.hpp, json.hpp, plots.hpp).
#include "schedulers/main_job/report.hpp"

#include <iostream>
#include <sstream>

#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "schedulers/main_job/analysis.hpp"
#include "schedulers/main_job/json.hpp"
#include "schedulers/main_job/plots.hpp"
#include "schedulers/main_job/tables.hpp"

namespace frontsteal::main_job {

namespace {

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// The short answer: what the run decided, first, in plain words.
std::string answer_text(const Analysis& a) {
  std::ostringstream s;
  s << "ANSWER (measured on " << a.machine << "; " << a.design_line << "):\n";
  for (const std::string& line : a.answer) s << "  " << line << "\n";
  if (a.answer.empty()) s << "  no stealing scheduler was run (see --schedulers)\n";
  if (!a.scale_answer.empty()) {
    s << "Scale, against the machine's own limit (the limit arm: P serial loops at once, each over the whole frame "
         "into buffers of its own; its throughput limit L = 1 / (sum of the copies' rates); limit-efficiency = "
         "L / T_P, paired per round):\n";
    for (const std::string& line : a.scale_answer) s << "  " << line << "\n";
  }
  return s.str();
}

// The heading lines above the table (terminal).
std::string terminal_heading(const Measured& m, const Analysis& a) {
  const Options& o = m.o;
  std::ostringstream s;
  s << "\nfrontsteal: " << o.scene << ", " << m.wl.model.surfaces.size() << " surfaces, " << o.frames << " frames x "
    << o.repeats << " passes, tolerance " << o.tolerance << " px, " << o.width << "x" << o.height << "\n\n"
    << answer_text(a) << "\n"
    << "ideal = T1 / min(P, " << m.cores << "); utilization = busy / (wall x P), summed over every frame; "
    << "imbalance = max/mean busy per frame, averaged; cpu, off-cpu = workers' thread CPU time and time "
    << "in the frame without a CPU, over wall x P\n"
    << "passes: " << o.repeats << " (" << m.repeats_note
    << "); T_P/T_ref = exp of the robust (Huber) estimate of the per-round log-ratios "
    << "with its 95 % t interval; verdict against +-" << fixed(100 * o.margin, 1) << " %, effect = change in time\n"
    << a.path_line << "\n"
    << a.interference_line << "\n"
    << a.spread_summary << "\n\n";
  return s.str();
}

// Where the time went: the account table with the lines that say how to read it.
std::string account_text(const Analysis& a) {
  if (a.rows.empty()) return {};
  return "where the time went (measured; % of P x T, T the harness's frame time, summed over every frame: "
         "loss_account.hpp; work at the limit's speed + inflation beyond the limit's = the items' work, split by "
         "the sampled surfaces' inflation against the serial loop in the same rounds, the limit arm's against "
         "the scheduler's; off_cpu taken out of the other terms; closes: |unaccounted| <= " +
         fixed(100 * kClosureBound, 0) + " %):\n" + account_table(a).markdown();
}

// The calibration arms' verdicts (--calibrate): the method tested on this machine, in this run.
std::string calibration_text(const Analysis& a) {
  if (a.calibration.empty()) return {};
  report::Table t({{"workers", "P"},
                   {"arm", "calibration arm", false},
                   {"planted", "planted (%)"},
                   {"realized", "realized (%)"},
                   {"interval", "ratio [95% CI]", false},
                   {"verdict", "verdict", false},
                   {"found", "found", false},
                   {"covered", "realized inside", false},
                   {"sd", "sd/round (%)"},
                   {"removed", "variance removed (%)"}});
  for (const CalibrationRow& r : a.calibration) {
    t.add_row({r.workers, r.label, fixed(100 * r.nominal, 1), fixed(100 * r.realized, 2), r.result.interval_text(),
               r.result.verdict_text(), r.nominal == 0 ? std::string("-") : (r.found() ? "yes" : "no"),
               r.covered() ? "yes" : "no", fixed(100 * r.result.c.chosen().sd, 2),
               fixed(100 * r.result.c.variance_removed, 1)});
  }
  return "calibration arms (the method tested in this run: the A/A twin must not be faster or slower, planted "
         "changes must be found):\n" +
         t.markdown();
}

std::string markdown_report(const Measured& m, const Analysis& a, const std::string& table) {
  const Options& o = m.o;
  std::ostringstream md;
  md << "# frontsteal main job (measured)\n\n"
     << "Scene `" << o.scene << "` (" << m.wl.model.surfaces.size() << " surfaces), " << o.frames
     << " frames along the camera path `" << ts::name(o.path) << "`, " << o.repeats << " passes (" << m.repeats_note
     << "), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height << ". Machine: " << a.machine
     << ". Commit " << FRONTSTEAL_GIT_COMMIT << ".\n\n"
     << "## Answer\n\n"
     << answer_text(a) << "\n"
     << "Verdicts: per round (the serial loop and every arm of one P once on one segment of the path, random order), "
        "the log-ratio "
     << "T_P[r] / T_ref[r]; exp of its Huber estimate (segments as blocks) with its 95 % Student-t interval (adjusted "
        "for the CPU speed probe "
     << "unless --no-adjust); faster / slower when the interval lies beyond +-" << fixed(100 * o.margin, 1)
     << " %, equivalent inside, inconclusive otherwise; effect = change in time. cpu and off-cpu: the "
     << "workers' thread CPU time and their time in the frame without a CPU, over wall x P.\n\n"
     << "**" << a.path_line << "; " << a.interference_line << ".**\n\n```\n"
     << a.spread_summary << "\n```\n\n"
     << table << '\n'
     << "## Where the time went\n\n"
     << account_text(a) << '\n'
     << a.child_note << (a.child_note.empty() ? "" : "\n") << a.tessellation_audit << ".\n\n"
     << a.remade << ".\n\n"
     << a.spread_line << ".\n\n"
     << a.noise_line << ".\n"
     << (a.calibration.empty() ? "" : "\n" + calibration_text(a));
  if (!a.warning.empty())
    md << "\n**" << a.warning.substr(0, a.warning.find('\n')) << "**\n\n```\n" << a.warning << "```\n";
  return md.str();
}

// The audit failures, on stderr; true when there were any.
bool report_problems(const Measured& m, const Analysis& a) {
  if (!a.problems) return false;
  std::cerr << kProgram << ": AUDIT FAILED:\n";
  if (a.serial_inconsistencies > 0) {
    std::cerr << "  serial loop: " << a.serial_inconsistencies << " surface-frames fail the tessellation audit\n";
  }
  for (const Cell& c : m.cells) {
    if (c.failed()) {
      std::cerr << "  " << c.scheduler << " P=" << c.workers << ": " << c.audit_failures << " frames not exactly-once, "
                << c.triangle_mismatches << " triangle mismatches, " << c.tessellation_inconsistencies
                << " surface-frames failing the tessellation audit; first: " << c.first_problem << '\n';
    }
  }
  return true;
}
}  // namespace

int write_results(const Measured& m, double elapsed_s) {
  const Options& o = m.o;
  const Analysis a = analyze(m);
  const std::string table = shown_table(m, a).markdown();
  std::cout << terminal_heading(m, a) << table << '\n'
            << account_text(a) << '\n'
            << a.child_note << a.tessellation_audit << '\n'
            << a.remade << '\n'
            << a.spread_line << '\n'
            << a.noise_line << '\n';
  if (!a.calibration.empty()) std::cout << '\n' << calibration_text(a);
  try {
    const report::ResultsDir dir(kProgram, o.out);
    const report::Table data = data_table(m, a);
    dir.write("frontsteal.md", markdown_report(m, a, table));
    dir.write("frontsteal.csv", data.csv());
    dir.write_json("frontsteal.json", results_json(m, a, data));
    if (!a.calibration.empty()) {
      dir.write("frontsteal-calibration.md", "# frontsteal calibration arms (measured)\n\nMachine: " + a.machine +
                                                 ". Commit " + FRONTSTEAL_GIT_COMMIT + ". " + a.design_line + ".\n\n" +
                                                 calibration_text(a));
      dir.write_json("frontsteal-calibration.json", calibration_json(m, a));
    }
    write_plots(m, a, dir);
    std::cout << "\nwrote " << dir.file("frontsteal.json").string() << ", .csv, .md"
              << (o.plot ? ", frontsteal-speedup.png, frontsteal-verdicts.png, frontsteal-frames.png, "
                           "frontsteal-account.png"
                         : "")
              << (a.calibration.empty() ? "" : ", frontsteal-calibration.{md,json}") << " (" << fixed(elapsed_s, 0)
              << " s)\n";
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  if (a.unreliable > 0) {
    // Last, on stdout and stderr, so it is the thing one sees.
    std::cout << '\n' << a.warning;
    std::cerr << kProgram << ": WARNING: " << a.unreliable << " of " << a.verdicts
              << " verdicts unreliable (reasons on stdout and in frontsteal.md)\n";
  }
  return report_problems(m, a) ? 1 : 0;
}

}  // namespace frontsteal::main_job
