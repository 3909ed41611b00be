// paper_options.cpp — frontsteal-paper's options through report::CommandLine (paper_options.hpp).
#include "papers/paper_options.hpp"

#include <string_view>

#include "reporting/command_line.hpp"

namespace frontsteal::papers {

namespace {

constexpr const char* kProgram = "frontsteal-paper";

constexpr const char* kDescription =
    R"(Regenerates the tables and the figure of Kumar, Chang & Manocha (SC'96, §6) beside the paper's numbers, on
procedural stand-ins with the paper's surface counts, and replays per-surface cost traces through
discrete-event models of the schedulers for P = 1 ... 64. Each command writes NAME.md, NAME.csv, NAME.json and
NAME.png into --out, stamped with machine, commit and date; every figure says "measured" or "simulated".
Measured comparisons carry a paired 95 % interval and a verdict; a noise monitor (/proc) marks the verdicts a
busy machine makes unreliable and says so.)";

constexpr const char* kFooter = R"(
Usage: frontsteal-paper COMMAND [options] (options may also come before COMMAND).
Exit status: 0 done, 1 a run failed (audit, I/O), 2 bad usage or scene, 3 no OpenGL for table2.)";

// --cost-multiplier K|auto|off → 0 auto, -1 off, else K in [1, 10000]; false when `v` is none of them.
bool parse_cost_multiplier(const std::string& v, int* k) {
  if (v == "auto" || v == "off") {
    if (k) *k = v == "auto" ? 0 : -1;
    return true;
  }
  try {
    std::size_t end = 0;
    const int n = std::stoi(v, &end);
    if (end != v.size() || n < 1 || n > 10000) return false;
    if (k) *k = n;
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

Options parse_options(int argc, char** argv, const std::vector<SubcommandSummary>& subcommands) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  CLI::App& app = cli.app();
  cli.out(o.out)->type_name("DIR");
  cli.app()
      .add_option("--scenes", o.scenes,
                  "comma-separated scenes instead of the command's stand-ins (plant:N, teapot, a file)")
      ->delimiter(',')
      ->type_name("L");
  cli.option("--scene", o.scene, "the scene of `trace`")->type_name("S");
  cli.option("--trace", o.trace, "the trace file of `trace` / `simulate` (default DIR/trace-<scene>.txt)")
      ->type_name("FILE");
  cli.option("--calibration", o.calibration,
             "use these costs instead of running the microbenchmarks (written by `calibrate`)")
      ->type_name("FILE");
  cli.option("--frames", o.frames, "frames along the camera path (orbit, then zoom)")
      ->type_name("F")
      ->check(CLI::Range(1, 100000));
  cli.option("--repeats", o.repeats,
             "rounds of each measured run: every scheduler, P and the serial loop once per round, in a fresh random "
             "order; comparisons from the per-round log-ratios (Huber estimate, t interval; probe-adjusted from 4 "
             "rounds on), medians for the frames/s columns")
      ->type_name("R")
      ->check(CLI::Range(1, 1000));
  cli.option("--passes", o.passes, "serial passes a trace's per-surface medians come from")
      ->type_name("K")
      ->check(CLI::Range(1, 100));
  cli.option("--max-p", o.max_p, "largest simulated processor count")
      ->type_name("P")
      ->check(CLI::Range(WorkerId{1}, WorkerId{1024}));
  cli.option("--updates", o.updates, "table2: pusher updates per scene")->type_name("U")->check(CLI::Range(1, 1000000));
  cli.option("--rate", o.rate, "table2: the pusher's target updates per second")
      ->type_name("R")
      ->check(CLI::Range(0.0, 1000.0));
  cli.flag("--null-renderer", o.null_renderer, "table2: count what would be drawn, no OpenGL");
  std::string multiplier = "auto";
  cli.option("--cost-multiplier", multiplier,
             "table2's tessellation-bound (\"paper-era\") row: each surface tessellated K times per tessellation "
             "frame, so the tessellators are slower than the pusher; auto: K = ceil(4 x tess/s / updates/s) of the "
             "scene's natural row (the paper's tessellators ran at about a quarter of the update rate), rescaled once "
             "if the bound row lands outside 3-5 updates per tessellation; off: natural rows only")
      ->type_name("K|auto|off")
      ->check(CLI::Validator(
          [](std::string& v) {
            return parse_cost_multiplier(v, nullptr) ? std::string()
                                                     : "expects auto, off or an integer in [1, 10000], got '" + v + "'";
          },
          ""));
  cli.seed(o.seed, "victim orders and annealing")
      ->type_name("S")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62));
  cli.option("--validation", o.validation,
             "fig8 / simulate: the simulator's held-out validation (validation.json, written by `validate`); its "
             "median |error| on speed-up ratios is drawn as a band around every simulated curve (default: "
             "DIR/validation.json when it exists; without one the curves have no band and the plot says so)")
      ->type_name("FILE");
  bool no_plot = false;
  cli.flag("--no-plot", no_plot, "do not run gnuplot (the .gp scripts and .dat files are still written)");
  cli.quiet(o.quiet);
  for (const SubcommandSummary& s : subcommands) {
    CLI::App* sub = app.add_subcommand(s.name, s.summary);
    sub->fallthrough();  // the parent's options after the subcommand's name
  }
  app.require_subcommand(1);
  cli.parse(argc, argv);
  for (const CLI::App* sub : app.get_subcommands()) o.command = sub->get_name();  // the one given
  parse_cost_multiplier(multiplier, &o.cost_multiplier);
  o.plot = !no_plot;
  return o;
}

}  // namespace frontsteal::papers
