// main_job_report.cpp — the main job's reporting (main_job_report.hpp): the heading and the table on stdout,
// frontsteal.md, and the closing lines; the analysis, the tables, the JSON and the plots come from their own
// files (main_job_analysis.hpp, main_job_tables.hpp, main_job_json.hpp, main_job_plots.hpp).
#include "schedulers/main_job_report.hpp"

#include <iostream>
#include <sstream>

#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "schedulers/main_job_analysis.hpp"
#include "schedulers/main_job_json.hpp"
#include "schedulers/main_job_plots.hpp"
#include "schedulers/main_job_tables.hpp"

namespace frontsteal::main_job {

namespace {

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// The heading lines above the table (terminal).
std::string terminal_heading(const Measured& m, const Analysis& a) {
  const Options& o = m.o;
  std::ostringstream s;
  s << "\nfrontsteal: " << o.scene << ", " << m.wl.model.surfaces.size() << " surfaces, " << o.frames << " frames x "
    << o.repeats << " repeats (medians), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height << "\n"
    << "machine: " << a.machine << " (measured, not simulated)\n"
    << "ideal = T1 / min(P, " << m.cores << "); utilization = busy / (wall x P), summed over every frame; "
    << "imbalance = max/mean busy per frame, averaged; cpu, off-cpu = workers' thread CPU time and time "
    << "in the frame without a CPU, over wall x P\n"
    << "repeats: " << o.repeats << " (" << m.repeats_note << "); T_P/T_ref = median of per-repeat ratios, "
    << "95 % bootstrap interval; verdict at 95 %, effect = change in path time\n"
    << a.path_line << "\n" << a.interference_line << "\n" << a.spread_summary << "\n\n";
  return s.str();
}

std::string markdown_report(const Measured& m, const Analysis& a, const std::string& table) {
  const Options& o = m.o;
  std::ostringstream md;
  md << "# frontsteal main job (measured)\n\n"
     << "Scene `" << o.scene << "` (" << m.wl.model.surfaces.size() << " surfaces), " << o.frames
     << " frames along the camera path `" << ts::name(o.path) << "`, " << o.repeats
     << " interleaved repeats (medians), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height
     << ". Machine: " << a.machine << ". Commit " << FRONTSTEAL_GIT_COMMIT << ".\n\n"
     << "Verdicts: median of the per-repeat ratios T_P[r] / T_ref[r] with its 95 % bootstrap interval; ahead / "
     << "behind when the interval lies below / above 1; effect = change in path time. cpu and off-cpu: the "
     << "workers' thread CPU time and their time in the frame without a CPU, over wall x P.\n\n"
     << "**" << a.path_line << "; " << a.interference_line << ".**\n\n```\n" << a.spread_summary << "\n```\n\n"
     << table << '\n' << a.child_note << (a.child_note.empty() ? "" : "\n") << a.tessellation_audit << ".\n\n"
     << a.spread_line << ".\n\n" << a.noise_line << ".\n";
  if (!a.warning.empty()) md << "\n**" << a.warning.substr(0, a.warning.find('\n')) << "**\n\n```\n" << a.warning << "```\n";
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
  std::cout << terminal_heading(m, a) << table << '\n' << a.child_note << a.tessellation_audit << '\n'
            << a.spread_line << '\n' << a.noise_line << '\n';
  try {
    const report::ResultsDir dir(kProgram, o.out);
    const report::Table data = data_table(m, a);
    dir.write("frontsteal.md", markdown_report(m, a, table));
    dir.write("frontsteal.csv", data.csv());
    dir.write_json("frontsteal.json", results_json(m, a, data));
    write_plots(m, a, dir);
    std::cout << "\nwrote " << dir.file("frontsteal.json").string() << ", .csv, .md"
              << (o.plot ? ", frontsteal-speedup.png, frontsteal-frames.png" : "") << " ("
              << fixed(elapsed_s, 0) << " s)\n";
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  if (a.unreliable > 0) {
    // Last, on stdout and stderr, so it is the thing one sees.
    std::cout << '\n' << a.warning;
    std::cerr << kProgram << ": WARNING: noisy machine: " << a.unreliable << " of " << a.verdicts
              << " verdicts unreliable (reasons on stdout and in frontsteal.md)\n";
  }
  return report_problems(m, a) ? 1 : 0;
}

}  // namespace frontsteal::main_job
