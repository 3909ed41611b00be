// options.cpp — frontsteal's command line (options.hpp): the --help text, --list, and every
// option through report::CommandLine (CLI11), with the checks CLI11 cannot express as validators.
#include "schedulers/main_job/options.hpp"

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "reporting/command_line.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/registry.hpp"
#include "schedulers/main_job/subcommands.hpp"

namespace frontsteal::main_job {

namespace fs = frontsteal;
namespace sc = frontsteal::sched;
namespace report = frontsteal::report;

namespace {

constexpr const char* kDescription =
    R"(Tessellates a scene along a deterministic camera path (an orbit of the whole model, then a zoom into a small
corner region: the case where round robin becomes imbalanced, paper §3) with a serial loop and with every
scheduler at P = 1 ... cores and oversubscribed (2 x cores), measured side by side in one run, and says first,
in plain words, whether stealing is faster than the locked queue and than the best other scheduler at each P,
and how close it comes to the machine's own limit: the limit arm runs P copies of the serial loop at once (each
over the whole frame into buffers of its own; --no-limit leaves it out), and every scheduler's limit-efficiency
L / T_P is measured against it, with the loss account of where the rest of P x T went (wake-up, items, claims,
the harness's checks, search, steals, the wait on ListTransient, the frame's end, time off the CPU).

How it measures. The run is made of ROUNDS. A round covers one segment of the path (--round-frames frames,
default 1) at one P, and runs the serial loop and every arm at that P once on it — every scheduler, and with
--calibrate the calibration arms — in a fresh random order (--order). A pass is one round per segment and P;
--repeats counts passes. Workers are pinned (--pin, the default: the two vCPUs of these VMs run at different
speeds). Every frame is timed by this program's own clock around the scheduler's run_frame call (the
scheduler's own figure is kept as a cross-check). Each comparison (a scheduler against the serial loop, and
against queue-mutex at the same P) is analysed on the per-round log-ratio of the two arms' times: a robust
location (Huber's M-estimate; --estimator) with segment effects removed and a Student-t 95 % interval, raw and
adjusted for the CPU speed probe timed just before each arm (regression adjustment); the ratio shown is its
exponential. Every scheduler is built afresh every --instance-frames frames (at a random heap offset), and
the rounds one instance ran form a cluster: the interval's error is cluster-robust, so it includes how much
two instances of the same code differ, not only how much rounds do.
Verdicts against the margin m (--margin, default 2 %): faster / slower when the whole interval lies beyond +-m,
equivalent when it lies inside +-m, inconclusive otherwise, with the rounds a run of this noise would need.
"unreliable" only when something invalidated the measurement: another process took the machine while the pair
ran (noise monitor, /proc), the co-runner did not run as asked, or an audit failed.
Every frame is audited: each surface tessellated exactly once, triangle count equal to the serial loop's,
and each trimmed surface's triangles tile its trimmed domain exactly (no overlap, no covered hole, (u, v) area
equal to the trim loops'). Any failure is reported and the exit status is 1.)";

constexpr const char* kFooter = R"(
--calibrate adds, at P = 1 and P = cores (both added to --threads for every scheduler when missing), arms that
test the method itself on this machine: an A/A twin (the
--calibrate-base scheduler under a second name: it must come out equivalent, never faster or slower) and the
same scheduler with planted extra work of 2, 5 and 10 % of its frame time, done after each frame inside the
timed region (they must come out slower; the base against the +5 % arm is a planted speed-up of 4.8 %). The
planted work is resized after the first pass from what it realized there; the sizes realized over the run are
measured by the same clock and reported with the verdicts (frontsteal-calibration.md).
--interference sets the pinning itself: pinned pins the workers, unpinned leaves every thread to the OS
(whatever --pin / --no-pin say).
Columns cpu and off-cpu: the workers' thread CPU time, and their time in the frame without a CPU
(descheduled, or asleep on a lock), both over wall x P like utilization; idle for lack of work shows as
utilization below cpu.

openmp-static-steal (LLVM libomp's static_steal) runs in a child process, frontsteal-llvm-openmp, built with
clang++-14 beside this program (FRONTSTEAL_LLVM_OPENMP=PATH overrides where it is); where it is missing its
rows read "not available" with the reason, and the run goes on. Its frames are timed by the child's clock (the
harness sees only the exchange with the child).
Round-robin cost spread: per frame, max/min over workers of the cost round robin (item i on worker i mod P)
gives them, from the serial warm-up pass's measured per-item times and from the cost estimates, and the
round-robin rows' measured busy time per worker; worst frame and median over frames (paper §3: 1:50).

Outputs in DIR: frontsteal.json (everything, per frame and per round), frontsteal.csv and frontsteal.md (the
answer, then the table), frontsteal-speedup.png (paired speed-up over the serial loop against P, with 95 %
intervals; open marks: not decided), frontsteal-verdicts.png (every scheduler against queue-mutex, interval and
margin), frontsteal-frames.png (frame time along the path), frontsteal-account.png (where the time went beyond
the items' work, with 1 - limit-efficiency); with --calibrate frontsteal-calibration.{md,json}.
All figures are measured on this machine; none are simulated.
Exit status: 0; 1 when an audit fails or a scheduler cannot run; 2 for bad usage (or a scene that cannot be
loaded).)";

}  // namespace

namespace {

// --list: every scheduler, with the ones the main job does not run marked.
[[noreturn]] void print_list() {
  for (const auto& s : sc::scheduler_registry()) {
    std::cout << std::left << std::setw(34) << s.name << s.summary
              << (s.contract == fs::Contract::kAtLeastOnce ? "  [at-least-once: not run on tessellation]" : "")
              << (s.variant ? "  [variant: only when named in --schedulers]" : "") << '\n';
  }
  std::cout << std::left << std::setw(34) << sc::kLlvmOpenMpName << sc::kLlvmOpenMpSummary
            << (sc::llvm_openmp_unavailable_reason().empty()
                    ? ""
                    : "  [not available: " + sc::llvm_openmp_unavailable_reason() + "]")
            << '\n';
  std::cout << std::left << std::setw(34) << sc::kLlvmOpenMpChunk1Name << sc::kLlvmOpenMpChunk1Summary
            << "  [variant: only when named in --schedulers]\n";
  std::exit(0);
}

// A CLI11 validator from a parser that says why a value is wrong ("" when it is right).
CLI::Validator validator(std::function<std::string(const std::string&)> why_not) {
  return CLI::Validator([why_not = std::move(why_not)](std::string& v) { return why_not(v); }, "");
}

// --schedulers (empty or "all": every exactly-once scheduler, and the LLVM child) → the names to run.
std::vector<std::string> chosen_schedulers(const std::vector<std::string>& asked, const report::CommandLine& cli) {
  std::vector<std::string> wanted;
  if (asked.empty() || (asked.size() == 1 && asked[0] == "all")) {
    for (const auto& s : sc::scheduler_registry()) {
      if (s.contract == fs::Contract::kExactlyOnce && !s.variant) wanted.push_back(s.name);
    }
    wanted.emplace_back(sc::kLlvmOpenMpName);  // a child process (llvm_openmp_child.hpp); "not available" if not built
    return wanted;
  }
  for (const auto& name : asked) {
    if (name == sc::kLlvmOpenMpName || name == sc::kLlvmOpenMpChunk1Name) {
      wanted.push_back(name);
      continue;
    }
    const sc::SchedulerInfo* s = sc::find_scheduler(name);
    if (!s) cli.usage_error("--schedulers: unknown scheduler '" + name + "' (see --list)");
    if (s->contract != fs::Contract::kExactlyOnce) {
      cli.usage_error("--schedulers: " + name +
                      " is at-least-once: a duplicated surface would be tessellated into "
                      "its buffer by two threads at once; the main job runs exactly-once schedulers only");
    }
    wanted.push_back(name);
  }
  return wanted;
}

}  // namespace

Options parse_options(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, subcommand_help() + kDescription, kFooter);
  bool list = false, no_plot = false;
  cli.flag("--list", list, "list the schedulers and exit");
  cli.option("--scene", o.scene, "teapot | teacup | teaspoon | plant:N[:seed] | path to a model file")->type_name("S");
  cli.app()
      .add_option("--schedulers", o.schedulers, "comma-separated scheduler names, or all (default all; see --list)")
      ->delimiter(',')
      ->type_name("L");
  std::vector<unsigned> threads;
  cli.threads(threads, "comma-separated worker counts P (default 1..cores, then 2 x cores)")->type_name("L");
  std::string path = "orbit-then-zoom";
  cli.option("--path", path,
             "camera path: orbit-then-zoom (half an orbit of the whole model, half a zoom into a corner), walkthrough "
             "(low among the parts, corner to corner), dense-zoom (from the overview to a close view of the densest "
             "region: a few surfaces' view-dependent cost dominates)")
      ->type_name("K")
      ->check(CLI::IsMember({"orbit-then-zoom", "walkthrough", "dense-zoom"}));
  cli.option("--frames", o.frames, "frames along the path")->type_name("F")->check(CLI::Range(1, 100000));
  std::string repeats = "auto";
  cli.option("--repeats", repeats,
             "passes over the path (a pass is one round per segment of --round-frames frames and P; at least 2 give "
             "an interval, segments being blocks). auto: a pilot of 3 "
             "passes measures the spread of every comparison's per-round log-ratio, then the run is sized so that a "
             "change of the margin would be found with 80 % power, within --budget (at least 5 passes)")
      ->type_name("R|auto")
      ->check(validator([&](const std::string& v) -> std::string {
        if (v == "auto") return {};
        try {
          std::size_t end = 0;
          const int r = std::stoi(v, &end);
          if (end == v.size() && r >= 1 && r <= 1000) return {};
        } catch (const std::exception&) {
        }
        return "expects auto or an integer in [1, 1000], got '" + v + "'";
      }));
  cli.option("--budget", o.budget_s, "seconds the measured rounds may take under --repeats auto")
      ->type_name("S")
      ->check(CLI::Range(1.0, 1e6));
  cli.option("--round-frames", o.round_frames,
             "frames per round: the path is split into segments of F frames, each a round in which every arm runs "
             "once (short rounds keep the members of a pair close in time)")
      ->type_name("F")
      ->check(CLI::Range(1, 100000));
  cli.option("--instance-frames", o.instance_frames,
             "a fresh instance of every scheduler every F frames of each pass, at a random heap offset, after an "
             "untimed warm-up on the frame before (what it learns from frame to frame carries over); rounds of one "
             "instance are analysed as a cluster. Two instances of the same code differ by a few per cent for as "
             "long as they live; 0 keeps one instance per run and analyses its rounds as independent (a control: that "
             "interval misses the instances' offsets)")
      ->type_name("F")
      ->check(CLI::Range(0, 100000));
  std::string order = "random";
  cli.option("--order", order,
             "order of the arms within a round: random (a fresh random order per round, from --seed), "
             "counterbalanced (A-B-B-A: every other round reversed), fixed (the same order every round: biased "
             "under drift, kept as a negative control)")
      ->type_name("K")
      ->check(CLI::IsMember({"random", "counterbalanced", "fixed"}));
  double margin_pct = 100 * o.margin;
  cli.option("--margin", margin_pct,
             "equivalence margin m (%): faster / slower when the whole 95 % interval lies beyond +-m, equivalent "
             "when inside")
      ->type_name("PCT")
      ->check(CLI::Range(0.01, 100.0));
  std::string estimator = "huber";
  cli.option("--estimator", estimator,
             "location of the per-round log-ratios: huber (Huber's M-estimate, robust to the rounds in which the "
             "machine changed speed inside one arm's run) or mean (least squares, the textbook t interval)")
      ->type_name("E")
      ->check(CLI::IsMember({"huber", "mean"}));
  bool no_adjust = false;
  cli.flag("--no-adjust", no_adjust,
           "verdicts from the raw interval instead of the one adjusted for the CPU speed probe (both are reported)");
  cli.flag("--calibrate", o.calibrate,
           "add the calibration arms at P = 1 and P = cores: an A/A twin and planted slowdowns of 2, 5 and 10 % of "
           "the base scheduler (see below)");
  cli.option("--calibrate-base", o.calibrate_base, "the scheduler the calibration arms copy")->type_name("NAME");
  bool no_pin = false;
  cli.flag("--pin", o.pin,
           "pin worker w (and the serial loop, as worker 0) to the w-th allowed CPU (the default: "
           "on these VMs the two vCPUs run at different speeds, and unpinned arms land on either, "
           "which widened the paired intervals 1.6-fold here)");
  cli.flag("--no-pin", no_pin, "leave every thread where the OS puts it");
  bool no_limit = false;
  cli.flag("--no-limit", no_limit,
           "leave out the limit arm: at every P, P copies of the serial loop running at once, each over the whole "
           "frame into buffers of its own (the machine's own throughput limit with P busy cores; every scheduler's "
           "limit-efficiency L / T_P is measured against it, paired per round, L = 1 / (sum of the copies' rates))");
  cli.flag("--reuse", o.reuse,
           "frame-to-frame reuse, as the paper's renderer does: a surface whose steps and trim polylines did not "
           "change since the frame before keeps its triangles (identical to recomputing them, audited when "
           "made), so a frame's work is the surfaces whose steps changed; the report gives the surfaces "
           "re-tessellated per frame. Every arm starts each round from the same kept state (the frame before "
           "the round's, run untimed). Default off: every surface every frame, the heavier load");
  std::string interference;
  cli.option("--interference", interference,
             "a co-runner child process busy-loops DUTY % (1-100, default 50) of each 10 ms on one core while the "
             "schedulers run (it is paused while the serial loop runs, so T1 stays the undisturbed reference). "
             "pinned: workers pinned as with --pin and the co-runner on worker 0's core (the asymmetric slowdown "
             "static lists cannot absorb); unpinned (default): nothing pinned, the OS places everything. Always "
             "killed and reaped at the end (and if frontsteal dies); its CPU time is reported apart and is not "
             "counted as noise (default off)")
      ->type_name("DUTY[,pinned|unpinned]")
      ->check(validator([](const std::string& v) {
        std::string why;
        return fi::parse_interference(v, &why) ? std::string() : "expects DUTY[,pinned|unpinned]: " + why;
      }));
  double noise_busy = 100 * o.noise.other_share, noise_spread = 100 * o.noise.spread;
  cli.option("--noise-busy", noise_busy,
             "share of the machine (%) other processes (or steal) may take before a run is unreliable")
      ->type_name("PCT")
      ->check(CLI::Range(0.0, 100.0));
  cli.option("--noise-spread", noise_spread,
             "spread max/min - 1 (%) of the serial loop's passes above which the spread line warns (information "
             "only: the verdicts rest on the paired rounds, not on the spread of single passes)")
      ->type_name("PCT")
      ->check(CLI::Range(0.0, 1000.0));
  cli.option("--tolerance", o.tolerance, "screen-space tolerance in pixels")
      ->type_name("PX")
      ->check(CLI::Range(0.01, 1000.0));
  cli.option("--grain", o.grain,
             "items per claim of the chunked schedulers (queue, counter, Chase-Lev, TBB, OpenMP) (default: each "
             "scheduler's own: N/(100P) for queue and counter, 1 for the others)")
      ->type_name("G")
      ->default_str("")
      ->check(CLI::Range(fs::ItemId{1}, std::numeric_limits<fs::ItemId>::max()));
  std::string size = "1280x720";
  cli.option("--size", size, "image size the steps are computed for")
      ->type_name("WxH")
      ->check(report::size_validator());
  cli.seed(o.seed, "seed of victim orders and of the annealing")->type_name("S");
  cli.out(o.out)->type_name("DIR");
  cli.flag("--no-plot", no_plot, "do not run gnuplot (the .gp scripts are still written)");
  std::string defect;
  cli.option(
         "--plant-defect", defect,
         "negative control: tessellate with a planted defect (wave1-bridge | drop-ear) to see the audit fail (exit 1)")
      ->type_name("D")
      ->check(CLI::IsMember({"wave1-bridge", "drop-ear"}));
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  if (list) print_list();

  o.path = *ts::camera_path_named(path);
  if (cli.app().count("--interference")) o.interference = fi::parse_interference(interference, nullptr);
  o.pin = !no_pin;
  if (o.interference) o.pin = o.interference->pinned;  // pinned set-up: workers pinned; unpinned: nothing is
  o.repeats = repeats == "auto" ? 0 : std::stoi(repeats);
  if (cli.app().count("--noise-busy")) o.noise.other_share = o.noise.steal_share = noise_busy / 100.0;
  o.noise.spread = noise_spread / 100.0;
  o.order = *measure::order_kind_named(order);
  o.margin = margin_pct / 100.0;
  o.adjust = !no_adjust;
  o.estimator = estimator == "mean" ? measure::Estimator::kMean : measure::Estimator::kHuber;
  std::tie(o.width, o.height) = report::parse_size(size);
  o.plot = !no_plot;
  if (!defect.empty()) o.planted_defect = *ts::planted_defect_named(defect);
  o.limit = !no_limit;
  o.threads.assign(threads.begin(), threads.end());
  if (o.threads.empty()) {
    for (unsigned p = 1; p <= hardware_cores(); ++p) o.threads.push_back(p);
    o.threads.push_back(2 * hardware_cores());
  }
  o.schedulers = chosen_schedulers(o.schedulers, cli);
  if (o.calibrate) {
    const sc::SchedulerInfo* base = sc::find_scheduler(o.calibrate_base);
    if (!base || base->contract != fs::Contract::kExactlyOnce) {
      cli.usage_error("--calibrate-base: '" + o.calibrate_base + "' is not an exactly-once scheduler (see --list)");
    }
    // The calibration arms are compared with their base at P = 1 and P = cores: it must run.
    if (std::find(o.schedulers.begin(), o.schedulers.end(), o.calibrate_base) == o.schedulers.end()) {
      o.schedulers.push_back(o.calibrate_base);
    }
    for (unsigned p : {1u, hardware_cores()}) {
      if (std::find(o.threads.begin(), o.threads.end(), p) == o.threads.end()) o.threads.push_back(p);
    }
    std::sort(o.threads.begin(), o.threads.end());
  }
  return o;
}

}  // namespace frontsteal::main_job
