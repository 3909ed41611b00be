// frontsteal-stress — the protocol on real threads for many frames: exactly-once audits, outcome histograms
// (in the manner of jcstress), chaos injection, fault injection and negative controls.
//
// Built twice: in the tsan preset (ThreadSanitizer; the ctest `stress` label) and in release (no sanitizer;
// `--rates` measures how often the store->load reordering of x86 actually duplicates items).
//
// This file parses the options and hands over: the modes are stress_modes.cpp's (frame-level cases in
// frame_cases.cpp, faults in fault_scenarios.cpp), the results files stress_report.cpp's.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "reporting/command_line.hpp"
#include "stress/stress_modes.hpp"
#include "stress/stress_options.hpp"
#include "stress/stress_report.hpp"
#include "stress/stress_targets.hpp"

using namespace frontsteal;
using namespace frontsteal::stress;
namespace report = frontsteal::report;

namespace {

constexpr const char* kDescription =
    R"(Runs the stealing protocol on real threads for many frames and audits every item of every frame (lost = 0
always; duplicates = 0 for exactly-once policies, counted for at-least-once ones). Prints a histogram of
outcomes per target and thread count, and writes markdown and JSON (stress.{md,json}, or rates.{md,json}).
Exits 1 on a lost item, a duplicate under an exactly-once policy, a negative control that was not caught,
or a failed fault scenario; 2 for bad usage.)";
constexpr const char* kFooter = R"(
Modes:
  (default)  the bounded suite: every target x P in --threads, the model checker's scenarios on real threads
             (--scenario-runs each), then the fault scenarios
  --rates    no chaos, no sanitizer expected (run it from the release build): the handshake raced head-on
             (--rounds rounds of --race-items items: duplicates per million rounds) and the frame-level
             duplicate rate per million items, for Paper, the exactly-once policies, and every one-step
             weakening of Fenced and Minimal)";

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.app().add_flag_callback(
      "--list",
      [] {
        for (const auto& t : targets()) {
          std::cout << t.name << "  (" << name(t.contract) << (t.negative_control ? ", negative control" : "") << ")\n";
        }
        std::exit(0);
      },
      "list the targets and exit");
  cli.flag("--rates", o.rates, "measure duplicate rates (see Modes)");
  cli.option("--seconds", o.seconds, "time per case")->check(CLI::PositiveNumber);
  cli.option("--frames", o.frames, "frames per case instead of a time bound (0: use --seconds)");
  cli.option("--control-seconds", o.control_seconds,
             "a negative control ignores --seconds and --frames: it runs "
             "until its planted defect is caught (the first duplicate), and fails only if this many seconds pass first")
      ->check(CLI::PositiveNumber);
  cli.option("--items", o.items, "items per frame");
  cli.option("--chaos", o.chaos, "chaos injections per million labelled accesses (0 disables)")
      ->check(CLI::Range(0u, 1000000u));
  auto all = targets();
  std::vector<std::string> names{"all"};
  for (const auto& t : all) names.push_back(t.name);
  cli.app()
      .add_option("--targets", o.targets, "comma-separated target names (see --list), or all [default all]")
      ->delimiter(',')
      ->check(CLI::IsMember(names).description("a name from --list"));
  cli.app()
      .add_option("--threads", o.threads, "comma-separated thread counts")
      ->delimiter(',')
      ->check(CLI::Range(1u, 256u));
  cli.seed(o.seed, "seed of costs and chaos");
  cli.out(o.out);
  cli.option("--rounds", o.rounds, "handshake-race rounds per policy in --rates");
  cli.option("--race-items", o.race_items, "items per handshake-race round")->check(CLI::Range(1u, 1u << 30));
  cli.option("--race-work", o.race_work, "owner's multiply-adds after each claimed item in a race round");
  cli.option("--scenario-runs", o.scenario_runs, "runs of each model-checking scenario per target");
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const auto started = std::chrono::steady_clock::now();
  const StressReport r = o.rates ? run_rates(o) : run_suite(o, started);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  try {
    write_results(o, r, seconds);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  std::printf("\n%s in %.1f s; results in %s\n", r.all_ok ? "all cases as expected" : "FAILURES", seconds,
              o.out.c_str());
  return r.all_ok ? 0 : 1;
}
