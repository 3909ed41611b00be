// frontsteal-stress-publication — greedy rendering's publication and reclamation (core/component_publication.hpp)
// on real threads, with chaos injected at its labelled sites; one case (what it runs and checks) is
// publication_case.hpp's. This file parses the options, runs every policy × P × slots and writes the table.
// Negative controls: Broken:ReuseWithoutGrace and Broken:PublishEachSurface must be caught; the run fails if not.
// Each runs until its first catch (up to --control-seconds), not for --seconds: how soon a pusher update overlaps a
// premature reuse depends on how the machine's load schedules the threads, so a fixed duration can miss it.
#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/publication_policies.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "stress/publication_case.hpp"

using namespace frontsteal;
using namespace frontsteal::stress;
using namespace frontsteal::stress::publication_stress;
namespace report = frontsteal::report;

namespace {

constexpr const char* kProgram = "frontsteal-stress-publication";
constexpr const char* kDescription =
    R"(Stress test of greedy rendering's triangle publication and buffer reclamation on real threads with chaos: a
pusher that never waits, P tessellators (the stealing scheduler, Fenced), the caller as frame driver. Audits every
pusher update for torn components, use of a slot after its reuse and components going back in time; the planted
defects Broken:ReuseWithoutGrace and Broken:PublishEachSurface must be caught. Build with the tsan preset for
ThreadSanitizer's verdict on the triangle cells as well. Exits 1 on any unexpected outcome, 2 for bad usage.)";

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription);
  cli.option("--seconds", o.seconds, "run time per case of the sound policy (per P x slots)")
      ->check(CLI::Range(0.01, 3600.0));
  cli.option("--control-seconds", o.control_seconds,
             "a negative control runs until its defect is caught; it fails "
             "only if this many seconds pass first")
      ->check(CLI::Range(0.01, 3600.0));
  cli.app()
      .add_option("--threads", o.threads, "tessellator counts, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1u, 256u));
  cli.app()
      .add_option("--slots", o.slots, "slots per component, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(2, 16));
  cli.option("--components", o.components, "components (1..4 surfaces each, seeded)")->check(CLI::Range(1u, 100000u));
  cli.option("--chaos", o.chaos, "chaos injections per million labelled accesses")->check(CLI::Range(0u, 1000000u));
  cli.seed(o.seed, "component sizes and chaos");
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  return o;
}

std::vector<CaseResult> run_all(const Options& o) {
  std::vector<CaseResult> results;
  using Runner = CaseResult (*)(const Options&, WorkerId, SlotIndex, bool);
  const std::vector<std::pair<Runner, bool>> policies{{&run_case<PublicationOrders>, false},
                                                      {&run_case<BrokenReuseWithoutGrace>, true},
                                                      {&run_case<BrokenPublishEachSurface>, true}};
  const std::size_t total = policies.size() * o.threads.size() * o.slots.size();
  for (const auto& [run, negative] : policies) {
    for (WorkerId p : o.threads) {
      for (SlotIndex s : o.slots) {
        results.push_back(run(o, p, s, negative));
        const CaseResult& r = results.back();
        if (!o.quiet) {
          std::cerr << kProgram << ": [" << results.size() << "/" << total << "] " << r.policy << " P=" << p
                    << " slots=" << s << ": " << r.frames << " frames, " << r.seconds << " s, " << r.updates
                    << " updates, torn " << r.torn << ", reuse " << r.reuse << ", backwards " << r.backwards << " -> "
                    << (r.passed() ? (negative ? "caught" : "ok") : "UNEXPECTED") << "\n";
        }
      }
    }
  }
  return results;
}

report::Table case_table(const std::vector<CaseResult>& results) {
  report::Table t({{"policy", "policy", false},
                   {"threads", "P"},
                   {"slots", "slots"},
                   {"frames", "frames"},
                   {"seconds", "seconds"},
                   {"updates", "updates"},
                   {"driver_waits", "driver waits"},
                   {"torn", "torn"},
                   {"reuse", "reuse"},
                   {"backwards", "backwards"},
                   {"lag", "lag histogram (frames behind: draws)", false},
                   {"negative_control", "control", false},
                   {"passed", "passed", false},
                   {"verdict", "verdict", false}});
  for (const CaseResult& r : results) {
    std::ostringstream lag;
    report::Json lag_json = report::Json::object();
    for (const auto& [behind, n] : r.lag) {
      lag << (lag.tellp() > 0 ? ", " : "") << behind << ": " << n;
      lag_json[std::to_string(behind)] = n;
    }
    const std::string catch_time =
        std::to_string(r.frames) + " frames, " + report::fixed_text(r.seconds * 1e3, 1) + " ms";
    const std::string verdict =
        r.passed() ? (r.negative_control ? "caught (negative control) after " + catch_time : "ok")
                   : (r.negative_control ? "FAIL: negative control not caught in " + catch_time : "FAIL");
    t.add_row({r.policy, r.threads, r.slots, r.frames, report::Cell::fixed(r.seconds, 3), r.updates, r.driver_waits,
               r.torn, r.reuse, r.backwards, report::Cell::shown_as(lag.str(), lag_json), r.negative_control,
               r.passed(), verdict});
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::vector<CaseResult> results = run_all(o);
  const bool ok = std::all_of(results.begin(), results.end(), [](const CaseResult& r) { return r.passed(); });
  const report::Table table = case_table(results);
  std::ostringstream md;
  md << "# Publication stress (measured, chaos " << o.chaos << " per million, " << o.seconds
     << " s per sound case; a negative control runs until caught, at most " << o.control_seconds << " s)\n\n"
     << table.markdown();
  report::Json js = report::document(kProgram, 2, "measured", FRONTSTEAL_GIT_COMMIT);
  js["chaos_per_million"] = o.chaos;
  js["cases"] = table.json();
  js["all_as_expected"] = ok;
  try {
    const report::ResultsDir dir(kProgram, o.out);
    dir.write("publication-stress.md", md.str());
    dir.write_json("publication-stress.json", js);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  std::cout << table.terminal();
  return ok ? 0 : 1;
}
