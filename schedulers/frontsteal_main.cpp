// frontsteal — the main job: every scheduler on the real tessellation workload, side by side.
//
// A scene (default: the generated 15,906-surface plant, the size of the paper's largest Fig. 8 model) is
// tessellated along a deterministic camera path — half an orbit of the whole model, half a zoom into a small
// corner region, where round robin becomes badly imbalanced (paper §3) — by a serial loop (T1) and by every
// scheduler at P = 1 … cores and oversubscribed. Repeats are interleaved (repeat r of every scheduler runs
// before repeat r+1 of any), so slow drifts of a noisy machine spread over all of them. Every frame is
// audited: each surface ran exactly once, the frame's triangle count equals the serial loop's, and every
// surface passed the tessellation's own audit (trimmed pieces tiled exactly, area equal to the trim loops').
//
// Options go through reporting/command_line.hpp (CLI11); the results (table, markdown, CSV, JSON, gnuplot)
// through reporting/ (report::Table, report::ResultsDir, nlohmann JSON): see write_results below.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <tuple>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/machine_info.hpp"
#include "core/paired_comparison.hpp"
#include "core/thread_pinning.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "schedulers/interference.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/noise_monitor.hpp"
#include "schedulers/registry.hpp"
#include "schedulers/round_robin_spread.hpp"
#include "schedulers/static_assignment.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif
#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif

namespace fs = frontsteal;
namespace sc = frontsteal::sched;
namespace ts = frontsteal::tess;
namespace st = frontsteal::stats;
namespace nz = frontsteal::noise;
namespace fi = frontsteal::interference;
namespace report = frontsteal::report;

namespace {

using frontsteal::cpu_model;
using frontsteal::median;
using report::Json;

constexpr const char* kProgram = "frontsteal";
// frontsteal.json's schema (docs/results-schema.md). 2: the common header of reporting/ (schema 1, written by
// hand, had no schema_version or program); every key of schema 1 is kept.
constexpr int kSchemaVersion = 2;

constexpr const char* kDescription = R"(Tessellates a scene along a deterministic camera path (an orbit of the whole model, then a zoom into a small
corner region: the case where round robin becomes imbalanced, paper §3) with a serial loop and with every
scheduler at P = 1 ... cores and oversubscribed (2 x cores), measured side by side in one run. Shows progress,
prints a table (frames/s, speed-up over the serial loop, % of ideal T1/P, utilization = busy / (wall x P),
CPU time and time off a CPU per worker, imbalance = max/mean busy, steals, lock waits, and per comparison the
median paired ratio with its 95 % bootstrap interval and a verdict) and writes JSON, CSV, markdown and PNG
plots (gnuplot). A noise monitor samples /proc before, during and after the measurement; when other processes
or the hypervisor took a share of the machine, or the serial loop's repeats spread too much, it prints a
warning and marks the verdicts it affects "unreliable".
Every frame is audited: each surface tessellated exactly once, triangle count equal to the serial loop's,
and each trimmed surface's triangles tile its trimmed domain exactly (no overlap, no covered hole, (u, v) area
equal to the trim loops'). Any failure is reported and the exit status is 1.)";

constexpr const char* kFooter = R"(
Verdicts: per repeat r, ratio = T_P[r] / T_ref[r] with T_ref the serial loop (same repeat) or queue-mutex at
the same P; "ahead" when the 95 % interval of the median ratio lies below 1, "behind" above 1, "no difference"
when it contains 1; the effect is (median ratio - 1) in % of path time (negative: faster).
Columns cpu and off-cpu: the workers' thread CPU time, and their time in the frame without a CPU
(descheduled, or asleep on a lock), both over wall x P like utilization; idle for lack of work shows as
utilization below cpu.

openmp-static-steal (LLVM libomp's static_steal) runs in a child process, frontsteal-llvm-openmp, built with
clang++-14 beside this program (FRONTSTEAL_LLVM_OPENMP=PATH overrides where it is); where it is missing its
rows read "not available" with the reason, and the run goes on.
Round-robin cost spread: per frame, max/min over workers of the cost round robin (item i on worker i mod P)
gives them, from the serial warm-up pass's measured per-item times and from the cost estimates, and the
round-robin rows' measured busy time per worker; worst frame and median over frames (paper §3: 1:50).

Outputs in DIR: frontsteal.json (everything, per frame), frontsteal.csv and frontsteal.md (the table),
frontsteal-speedup.png (speed-up against P), frontsteal-frames.png (frame time along the path).
All figures are measured on this machine; none are simulated.
Exit status: 0; 1 when an audit fails or a scheduler cannot run; 2 for bad usage (or a scene that cannot be
loaded).)";

struct Options {
  std::string scene = "plant:15906";
  std::vector<std::string> schedulers;  // empty: all exactly-once ones
  std::vector<fs::WorkerId> threads;
  int frames = 24;
  ts::CameraPathKind path = ts::CameraPathKind::orbit_then_zoom;
  std::optional<fi::InterferenceSpec> interference;  // absent: off
  int repeats = 0;  // 0: auto (see --repeats)
  double budget_s = 180;
  bool pin = false;
  nz::Thresholds noise;
  double tolerance = 1.0;
  fs::ItemId grain = 0;
  int width = 1280, height = 720;
  std::uint64_t seed = 1;
  std::string out = "out";
  bool plot = true;
  bool quiet = false;
  ts::PlantedDefect planted_defect = ts::PlantedDefect::none;
};

unsigned hardware_cores() { return std::max(1u, std::thread::hardware_concurrency()); }

// --list: every scheduler, with the ones the main job does not run marked.
[[noreturn]] void print_list() {
  for (const auto& s : sc::scheduler_registry()) {
    std::cout << std::left << std::setw(22) << s.name << s.summary
              << (s.contract == fs::Contract::kAtLeastOnce ? "  [at-least-once: not run on tessellation]" : "") << '\n';
  }
  std::cout << std::left << std::setw(22) << sc::kLlvmOpenMpName << sc::kLlvmOpenMpSummary
            << (sc::llvm_openmp_unavailable_reason().empty() ? "" : "  [not available: " + sc::llvm_openmp_unavailable_reason() + "]")
            << '\n';
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
      if (s.contract == fs::Contract::kExactlyOnce) wanted.push_back(s.name);
    }
    wanted.emplace_back(sc::kLlvmOpenMpName);  // a child process (llvm_openmp_child.hpp); "not available" if not built
    return wanted;
  }
  for (const auto& name : asked) {
    if (name == sc::kLlvmOpenMpName) {
      wanted.push_back(name);
      continue;
    }
    const sc::SchedulerInfo* s = sc::find_scheduler(name);
    if (!s) cli.usage_error("--schedulers: unknown scheduler '" + name + "' (see --list)");
    if (s->contract != fs::Contract::kExactlyOnce) {
      cli.usage_error("--schedulers: " + name + " is at-least-once: a duplicated surface would be tessellated into "
                      "its buffer by two threads at once; the main job runs exactly-once schedulers only");
    }
    wanted.push_back(name);
  }
  return wanted;
}

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  bool list = false, no_plot = false;
  cli.flag("--list", list, "list the schedulers and exit");
  cli.option("--scene", o.scene, "teapot | teacup | teaspoon | plant:N[:seed] | path to a model file")->type_name("S");
  cli.app().add_option("--schedulers", o.schedulers, "comma-separated scheduler names, or all (default all; see --list)")
      ->delimiter(',')->type_name("L");
  std::vector<unsigned> threads;
  cli.threads(threads, "comma-separated worker counts P (default 1..cores, then 2 x cores)")->type_name("L");
  std::string path = "orbit-then-zoom";
  cli.option("--path", path,
             "camera path: orbit-then-zoom (half an orbit of the whole model, half a zoom into a corner), walkthrough "
             "(low among the parts, corner to corner), dense-zoom (from the overview to a close view of the densest "
             "region: a few surfaces' view-dependent cost dominates)")
      ->type_name("K")->check(CLI::IsMember({"orbit-then-zoom", "walkthrough", "dense-zoom"}));
  cli.option("--frames", o.frames, "frames along the path")->type_name("F")->check(CLI::Range(1, 100000));
  std::string repeats = "auto";
  cli.option("--repeats", repeats,
             "interleaved runs of the path per scheduler and P; medians, paired ratios and their bootstrap intervals "
             "are reported. auto: 10 when the warm-up pass predicts they fit in --budget, else as many as fit, at "
             "least 5; rounds stop early (not below 5) once the budget is spent")
      ->type_name("R|auto")->check(validator([&](const std::string& v) -> std::string {
        if (v == "auto") return {};
        try {
          std::size_t end = 0;
          const int r = std::stoi(v, &end);
          if (end == v.size() && r >= 1 && r <= 1000) return {};
        } catch (const std::exception&) {
        }
        return "expects auto or an integer in [1, 1000], got '" + v + "'";
      }));
  cli.option("--budget", o.budget_s, "seconds the measured repeats may take under --repeats auto")
      ->type_name("S")->check(CLI::Range(1.0, 1e6));
  cli.flag("--pin", o.pin, "pin worker w (and the serial loop, as worker 0) to the w-th allowed CPU (off by default; "
                           "the \"spread of the repeats\" line says whether it narrows them)");
  std::string interference;
  cli.option("--interference", interference,
             "a co-runner child process busy-loops DUTY % (1-100, default 50) of each 10 ms on one core while the "
             "schedulers run (it is paused while the serial loop runs, so T1 stays the undisturbed reference). "
             "pinned: workers pinned as with --pin and the co-runner on worker 0's core (the asymmetric slowdown "
             "static lists cannot absorb); unpinned (default): nothing pinned, the OS places everything. Always "
             "killed and reaped at the end (and if frontsteal dies); its CPU time is reported apart and is not "
             "counted as noise (default off)")
      ->type_name("DUTY[,pinned|unpinned]")->check(validator([](const std::string& v) {
        std::string why;
        return fi::parse_interference(v, &why) ? std::string() : "expects DUTY[,pinned|unpinned]: " + why;
      }));
  double noise_busy = 100 * o.noise.other_share, noise_spread = 100 * o.noise.spread;
  cli.option("--noise-busy", noise_busy,
             "share of the machine (%) other processes (or steal) may take before a run is unreliable")
      ->type_name("PCT")->check(CLI::Range(0.0, 100.0));
  cli.option("--noise-spread", noise_spread,
             "spread max/min - 1 (%) of the serial loop's repeats above which a run is unreliable")
      ->type_name("PCT")->check(CLI::Range(0.0, 1000.0));
  cli.option("--tolerance", o.tolerance, "screen-space tolerance in pixels")->type_name("PX")->check(CLI::Range(0.01, 1000.0));
  cli.option("--grain", o.grain,
             "items per claim of the chunked schedulers (queue, counter, Chase-Lev, TBB, OpenMP) (default: each "
             "scheduler's own: N/(100P) for queue and counter, 1 for the others)")
      ->type_name("G")->default_str("")->check(CLI::Range(fs::ItemId{1}, std::numeric_limits<fs::ItemId>::max()));
  std::string size = "1280x720";
  cli.option("--size", size, "image size the steps are computed for")->type_name("WxH")->check(report::size_validator());
  cli.seed(o.seed, "seed of victim orders and of the annealing")->type_name("S");
  cli.out(o.out)->type_name("DIR");
  cli.flag("--no-plot", no_plot, "do not run gnuplot (the .gp scripts are still written)");
  std::string defect;
  cli.option("--plant-defect", defect,
             "negative control: tessellate with a planted defect (wave1-bridge | drop-ear) to see the audit fail (exit 1)")
      ->type_name("D")->check(CLI::IsMember({"wave1-bridge", "drop-ear"}));
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  if (list) print_list();

  o.path = *ts::camera_path_named(path);
  if (cli.app().count("--interference")) o.interference = fi::parse_interference(interference, nullptr);
  if (o.interference && o.interference->pinned) o.pin = true;  // pinned set-up: workers pinned as by --pin
  o.repeats = repeats == "auto" ? 0 : std::stoi(repeats);
  if (cli.app().count("--noise-busy")) o.noise.other_share = o.noise.steal_share = noise_busy / 100.0;
  o.noise.spread = noise_spread / 100.0;
  std::tie(o.width, o.height) = report::parse_size(size);
  o.plot = !no_plot;
  if (!defect.empty()) o.planted_defect = *ts::planted_defect_named(defect);
  o.threads.assign(threads.begin(), threads.end());
  if (o.threads.empty()) {
    for (unsigned p = 1; p <= hardware_cores(); ++p) o.threads.push_back(p);
    o.threads.push_back(2 * hardware_cores());
  }
  o.schedulers = chosen_schedulers(o.schedulers, cli);
  return o;
}

// The workload: the scene prepared once, its per-frame views, and one output buffer per surface.
struct Workload {
  ts::Model model;
  std::vector<ts::PreparedSurface> prepared;
  std::vector<ts::TriangleBuffers> buffers;  // per surface: every scheduler writes the same buffers
  std::vector<ts::Camera> cameras;
  std::vector<ts::Frustum> frusta;
  ts::TessellationSettings settings;
  std::vector<std::uint64_t> serial_triangles;  // per frame, from the serial loop: the reference
  std::vector<std::uint64_t> serial_inconsistencies;  // per frame: surfaces whose tessellation audit failed
  std::vector<std::uint64_t> serial_capped;           // per frame: surfaces held at the step cap
};

// One scheduler at one P: what the interleaved repeats gathered.
struct Cell {
  std::string scheduler;
  fs::WorkerId workers = 0;
  std::unique_ptr<sc::Scheduler> instance;
  std::unique_ptr<sc::LlvmOpenMpChild> child;      // openmp-static-steal: the child process instead of instance
  std::string unavailable;                         // why this cell could not run ("" when it ran)
  double setup_ms = 0;                             // construction (annealing included)
  std::vector<double> path_ms;                     // per repeat
  std::vector<std::vector<double>> frame_ms;       // [repeat][frame]
  fs::WorkerFrameStats totals;                     // summed over every frame of every repeat
  std::vector<fs::WorkerFrameStats> per_worker;    // [worker], summed over every frame of every repeat
  nz::Usage usage;                                 // the machine while this cell's paths ran (all repeats)
  std::vector<std::vector<double>> busy_ratio;     // [repeat][frame]: max/min of the workers' busy time
  double busy_over_available = 0, available = 0;   // Σ busy, Σ wall × P (ns)
  double imbalance_sum = 0, imbalance_max = 0;
  std::uint64_t frames_run = 0;
  std::uint64_t audit_failures = 0, triangle_mismatches = 0;
  std::uint64_t tessellation_inconsistencies = 0;  // surfaces × frames whose tessellation audit failed
  std::string first_problem;
  bool failed() const { return audit_failures || triangle_mismatches || tessellation_inconsistencies; }
};

class Progress {
 public:
  Progress(bool quiet, std::size_t total) : quiet_(quiet), total_(total), start_(std::chrono::steady_clock::now()) {}
  void set_total(std::size_t total) { total_ = total; }
  void step(const std::string& what) {
    ++done_;
    if (quiet_) return;
    const double elapsed = seconds();
    const double eta = done_ ? elapsed / done_ * (total_ - done_) : 0;
    std::fprintf(stderr, "[%3zu/%zu %5.0fs, ~%.0fs left] %s\n", done_, total_, elapsed, eta, what.c_str());
  }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool quiet_;
  std::size_t total_, done_ = 0;
  std::chrono::steady_clock::time_point start_;
};

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// The worker id this thread is pinned as under --pin (-1: not pinned). Pinning happens on a thread's first
// item of a frame rather than inside each scheduler, so it reaches the threads of oneTBB and OpenMP too,
// which we do not create.
thread_local int t_pinned_as = -1;

// One comparison as the table shows it: the verdict, or "unreliable (verdict)" when the noise monitor says
// the machine was not ours while it was measured.
struct ShownComparison {
  st::Comparison c;
  bool reliable = true;
  std::string noise_reason;  // why not reliable
  std::string verdict_text() const {
    std::string v = st::to_string(c.verdict);
    if (c.verdict != st::Verdict::kTooFewRepeats) v += " " + std::string(c.effect_pct >= 0 ? "+" : "") + fixed(c.effect_pct, 1) + " %";
    return reliable ? v : "unreliable (" + v + ")";
  }
  std::string interval_text() const {
    return fixed(c.ratio.median, 3) + " [" + fixed(c.ratio.low, 3) + ", " + fixed(c.ratio.high, 3) + "]";
  }
  Json json() const {
    return {{"ratio_median", c.ratio.median}, {"ci95_low", c.ratio.low}, {"ci95_high", c.ratio.high}, {"pairs", c.pairs},
            {"effect_pct", c.effect_pct}, {"verdict", reliable ? st::to_string(c.verdict) : "unreliable"},
            {"verdict_if_reliable", st::to_string(c.verdict)}, {"reliable", reliable}};
  }
};

Json usage_json(const nz::Usage& u, const nz::Thresholds& t) {
  return {{"wall_s", u.wall_s}, {"windows", u.windows}, {"ticks", u.total_ticks}, {"other_share", u.other_share()},
          {"steal_share", u.steal_share()}, {"busy", nz::assess(u, t).busy}};
}

// {"worst", "worst_frame", "median", "per_frame"}; infinity (a worker with nothing) is null.
Json spread_json(const sc::CostSpread& c) {
  auto number = [](double v) { return std::isinf(v) ? Json(nullptr) : Json(v); };
  Json per_frame = Json::array();
  for (double v : c.per_frame) per_frame.push_back(number(v));
  return {{"worst", number(c.worst)}, {"worst_frame", c.worst_frame}, {"median", number(c.median)}, {"per_frame", per_frame}};
}

// ---- results: the analysis (verdicts, noise, spreads) and its reporting ---------------------------------

// What the measurement leaves for the report: references into main's state, read only.
struct Measured {
  const Options& o;
  unsigned cores;
  const Workload& wl;
  const ts::DenseRegion& dense;
  const std::vector<std::vector<double>>& item_ns;        // [frame][surface]: warm-up pass, ns
  const std::vector<std::vector<double>>& item_estimate;  // [frame][surface]: cost estimate
  const std::vector<double>& serial_path_ms;
  const std::vector<std::vector<double>>& serial_frame_ms;
  const std::vector<nz::Usage>& serial_usage;
  const std::vector<Cell>& cells;
  const std::vector<Cell>& not_available;
  nz::ProcSample at_start, measure_start, measure_end, at_end;
  std::string repeats_note;
  int co_runner_cpu;  // -1: not pinned (or no co-runner)
};

struct Row {
  const Cell* cell = nullptr;
  double path_ms = 0, fps = 0, speedup = 0, ideal_pct = 0, utilization = 0, imbalance_mean = 0;
  double cpu_pct = 0, off_cpu_pct = 0, spread_pct = 0;
  ShownComparison vs_serial;
  std::optional<ShownComparison> vs_queue;  // absent for queue-mutex itself, or when it was not run
};

struct SpreadRow {
  fs::WorkerId p;
  sc::CostSpread measured, estimated;
  std::optional<sc::CostSpread> busy;  // from the round-robin row, when it ran at this P
};

// Everything the table, the files and the closing lines say.
struct Analysis {
  double t1_ms = 0, serial_spread = 0;
  nz::Usage before_usage, during_usage, after_usage;
  std::vector<std::string> noise_warnings;  // run-wide reasons: every verdict is unreliable
  std::vector<Row> rows;
  std::size_t verdicts = 0, unreliable = 0;
  bool problems = false;
  std::vector<SpreadRow> spreads;
  double co_runner_core_share = 0;
  std::uint64_t serial_inconsistencies = 0, capped_total = 0, capped_max = 0;
  std::string machine, path_line, spread_line, noise_line, spread_summary, interference_line, warning,
      tessellation_audit, child_note;
};

std::vector<double> frame_medians(const std::vector<std::vector<double>>& per_repeat, int frames) {
  std::vector<double> out;
  for (int f = 0; f < frames; ++f) {
    std::vector<double> v;
    for (const auto& rep : per_repeat) v.push_back(rep[f]);
    out.push_back(median(v));
  }
  return out;
}

// Noise: the machine before (loading and warm-up), during (every measured path, added up) and after; and
// the spread of the serial loop's repeats. Each makes every verdict unreliable; a busy machine during one
// cell's paths (or its reference's) makes that comparison unreliable.
void judge_rows(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.t1_ms = median(m.serial_path_ms);
  a.before_usage = nz::usage_between(m.at_start, m.measure_start);
  a.during_usage = nz::usage_between(m.measure_start, m.measure_end);
  a.after_usage = nz::usage_between(m.measure_end, m.at_end);
  nz::Usage serial_total;
  for (const nz::Usage& u : m.serial_usage) serial_total += u;
  a.serial_spread = nz::spread_of(m.serial_path_ms);
  if (const auto x = nz::assess(a.before_usage, o.noise); x.busy) a.noise_warnings.push_back("before the measurement: " + x.reason);
  if (const auto x = nz::assess(a.during_usage, o.noise); x.busy) a.noise_warnings.push_back("during the measurement: " + x.reason);
  if (const auto x = nz::assess(a.after_usage, o.noise); x.busy) a.noise_warnings.push_back("after the measurement: " + x.reason);
  if (a.serial_spread > o.noise.spread) {
    a.noise_warnings.push_back("the serial loop's repeats spread by " + fixed(100 * a.serial_spread, 1) +
                               " % (max/min - 1; threshold " + fixed(100 * o.noise.spread, 1) + " %)");
  }
  auto judge = [&](const std::vector<double>& candidate, const std::vector<double>& reference, nz::Usage usage) {
    ShownComparison sc_;
    sc_.c = st::compare_paired(candidate, reference);
    const nz::Assessment x = nz::assess(usage, o.noise);
    if (!a.noise_warnings.empty() || x.busy) {
      sc_.reliable = false;
      sc_.noise_reason = x.busy ? x.reason : a.noise_warnings.front();
    }
    return sc_;
  };
  auto queue_cell = [&](fs::WorkerId p) -> const Cell* {
    for (const Cell& q : m.cells) {
      if (q.scheduler == "queue-mutex" && q.workers == p) return &q;
    }
    return nullptr;
  };
  for (const Cell& c : m.cells) {
    Row row{};
    row.cell = &c;
    row.path_ms = median(c.path_ms);
    row.fps = 1000.0 * o.frames / row.path_ms;
    row.speedup = a.t1_ms / row.path_ms;
    const double ideal_ms = a.t1_ms / std::min<double>(c.workers, m.cores);
    row.ideal_pct = 100.0 * ideal_ms / row.path_ms;
    row.utilization = c.available > 0 ? 100.0 * c.busy_over_available / c.available : 0;
    row.imbalance_mean = c.frames_run ? c.imbalance_sum / c.frames_run : 0;
    if (c.available > 0) {
      row.cpu_pct = 100.0 * static_cast<double>(c.totals.cpu_ns) / c.available;
      row.off_cpu_pct = 100.0 * static_cast<double>(std::max<std::int64_t>(0, c.totals.active_ns - c.totals.cpu_ns)) /
                        c.available;
    }
    row.spread_pct = 100.0 * nz::spread_of(c.path_ms);
    nz::Usage with_serial = c.usage;
    with_serial += serial_total;
    row.vs_serial = judge(c.path_ms, m.serial_path_ms, with_serial);
    ++a.verdicts;
    if (!row.vs_serial.reliable) ++a.unreliable;
    if (const Cell* q = queue_cell(c.workers); q && q != &c) {
      nz::Usage with_queue = c.usage;
      with_queue += q->usage;
      row.vs_queue = judge(c.path_ms, q->path_ms, with_queue);
      ++a.verdicts;
      if (!row.vs_queue->reliable) ++a.unreliable;
    }
    a.rows.push_back(row);
    if (c.failed()) a.problems = true;
  }
}

// The camera path, and how much a few surfaces dominate: the 16 costliest surfaces' share of a frame's
// estimated cost.
std::string path_line(const Measured& m) {
  const Options& o = m.o;
  std::ostringstream line;
  line << "camera path: " << ts::name(o.path);
  if (o.path == ts::CameraPathKind::dense_zoom) {
    const glm::dvec3 c = m.dense.box.centre();
    line << " (ends at the densest region: " << m.dense.surfaces << " surfaces centred in one grid cell of edge "
         << fixed(m.dense.cell_edge, 2) << " (the median control-box diagonal), around (" << fixed(c.x, 1) << ", "
         << fixed(c.y, 1) << ", " << fixed(c.z, 1) << "), box diagonal "
         << fixed(glm::length(m.dense.box.hi - m.dense.box.lo), 2) << ")";
  }
  double top_max = 0;
  int top_frame = 0;
  for (int f = 0; f < o.frames; ++f) {
    std::vector<double> c = m.item_estimate[f];
    const std::size_t k = std::min<std::size_t>(16, c.size());
    std::partial_sort(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(k), c.end(), std::greater<>());
    double top = 0, total = 0;
    for (std::size_t i = 0; i < c.size(); ++i) (i < k ? top : total) += c[i];
    total += top;
    if (total > 0 && top / total > top_max) {
      top_max = top / total;
      top_frame = f;
    }
  }
  line << "; the 16 costliest surfaces carry up to " << fixed(100 * top_max, 1)
       << " % of a frame's estimated cost (frame " << top_frame << ")";
  return line.str();
}

// The round-robin cost spread per P >= 2 (round_robin_spread.hpp), and its summary lines.
void cost_spreads(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  for (fs::WorkerId p : o.threads) {
    if (p < 2) continue;
    SpreadRow r{p, sc::round_robin_spread(m.item_ns, p), sc::round_robin_spread(m.item_estimate, p), std::nullopt};
    for (const Cell& c : m.cells) {
      if (c.scheduler != "round-robin" || c.workers != p || c.busy_ratio.empty()) continue;
      r.busy = sc::summarize_spread(frame_medians(c.busy_ratio, o.frames));  // median over repeats, per frame
    }
    a.spreads.push_back(std::move(r));
  }
  using sc::ratio_text;
  std::ostringstream s;
  s << "round-robin cost spread (max/min over workers of the per-frame cost, item i on worker i mod P; "
       "worst frame / median over frames; paper §3: 1:50 for static schemes):";
  if (a.spreads.empty()) s << " no P >= 2 was run";
  for (const SpreadRow& r : a.spreads) {
    s << "\n  P=" << r.p << ": serial loop's measured per-item times dealt round robin " << ratio_text(r.measured.worst)
      << " (frame " << r.measured.worst_frame << ") / " << ratio_text(r.measured.median) << "; cost estimates "
      << ratio_text(r.estimated.worst) << " / " << ratio_text(r.estimated.median) << "; round-robin row's busy time "
      << (r.busy ? ratio_text(r.busy->worst) + " / " + ratio_text(r.busy->median) : std::string("not run"));
  }
  a.spread_summary = s.str();
}

// The one-line summaries: spread of the repeats, noise, interference, tessellation audit, the LLVM child,
// and the noise warning (empty when every verdict is reliable).
void summary_lines(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.machine = cpu_model() + ", " + std::to_string(m.cores) + " hardware threads";
  a.path_line = path_line(m);
  std::vector<double> cell_spreads;
  for (const Row& r : a.rows) cell_spreads.push_back(r.spread_pct);
  std::ostringstream spread;
  spread << "spread of the repeats (max/min - 1): serial loop " << fixed(100 * a.serial_spread, 1)
         << " %; schedulers: median " << fixed(median(cell_spreads), 1) << " %, max "
         << fixed(cell_spreads.empty() ? 0.0 : *std::max_element(cell_spreads.begin(), cell_spreads.end()), 1)
         << " % (workers pinned: " << (o.pin ? "yes, --pin" : "no") << ")";
  a.spread_line = spread.str();
  std::ostringstream noise;
  noise << "noise monitor: other processes / steal, as a share of the machine: before "
        << fixed(100 * a.before_usage.other_share(), 1) << " / " << fixed(100 * a.before_usage.steal_share(), 1)
        << " %, during " << fixed(100 * a.during_usage.other_share(), 1) << " / "
        << fixed(100 * a.during_usage.steal_share(), 1) << " %, after " << fixed(100 * a.after_usage.other_share(), 1)
        << " / " << fixed(100 * a.after_usage.steal_share(), 1) << " %; load average " << fixed(m.at_start.load1, 2)
        << " before, " << fixed(m.at_end.load1, 2) << " after (thresholds: " << fixed(100 * o.noise.other_share, 0)
        << " % busy, " << fixed(100 * o.noise.spread, 0) << " % spread)";
  a.noise_line = noise.str();
  nz::Usage cells_usage;
  for (const Cell& c : m.cells) cells_usage += c.usage;
  const double ticks_per_s = static_cast<double>(sysconf(_SC_CLK_TCK));
  a.co_runner_core_share =
      cells_usage.wall_s > 0 ? static_cast<double>(cells_usage.known_ticks) / (cells_usage.wall_s * ticks_per_s) : 0;
  a.interference_line = "interference: off";
  if (o.interference) {
    a.interference_line = "interference: ON, a co-runner child process busy-looping " + o.interference->describe() +
                          ", during every scheduler row (paused during the serial loop: T1 is undisturbed); it used " +
                          fixed(100 * a.co_runner_core_share, 1) + " % of one core while the schedulers ran " +
                          "(its own CPU time from /proc/<pid>/stat, reported here and not counted as noise)";
  }
  if (a.unreliable > 0) {
    std::ostringstream warning;
    warning << "WARNING: noisy machine: " << a.unreliable << " of " << a.verdicts
            << " verdicts are marked unreliable. Reasons:\n";
    for (const auto& w : a.noise_warnings) warning << "  - " << w << "\n";
    std::size_t cell_flags = 0;
    for (const Row& r : a.rows) {
      if (!r.vs_serial.reliable && r.vs_serial.noise_reason != (a.noise_warnings.empty() ? "" : a.noise_warnings.front())) {
        if (cell_flags++ < 5) {
          warning << "  - while " << r.cell->scheduler << " P=" << r.cell->workers << " or its reference ran: "
                  << r.vs_serial.noise_reason << "\n";
        }
      }
    }
    if (cell_flags > 5) warning << "  - ... and " << cell_flags - 5 << " more scheduler/P cells\n";
    warning << "Re-run on a quiet machine before drawing conclusions from these verdicts.\n";
    a.warning = warning.str();
  }
  for (int f = 0; f < o.frames; ++f) {
    a.serial_inconsistencies += m.wl.serial_inconsistencies[f];
    a.capped_total += m.wl.serial_capped[f];
    a.capped_max = std::max(a.capped_max, m.wl.serial_capped[f]);
  }
  if (a.serial_inconsistencies > 0) a.problems = true;
  // One line that says what "audit ok" covers, and what it found.
  std::ostringstream audit;
  audit << "tessellation audit (every surface of every frame, every run: trimmed pieces tiled exactly, "
           "(u, v) area = trim-loop area): "
        << a.serial_inconsistencies << " inconsistencies in the serial loop; surfaces held at the "
        << m.wl.settings.max_steps << "-step cap (deviation may exceed " << o.tolerance << " px there): "
        << a.capped_total << " surface-frames, at most " << a.capped_max << " per frame";
  a.tessellation_audit = audit.str();
  std::ostringstream child;  // how openmp-static-steal ran, and the proof that static_steal was in effect
  for (const Cell& c : m.cells) {
    if (c.child) {
      child << sc::kLlvmOpenMpName << " P=" << c.workers << ": child process " << sc::llvm_openmp_child_path()
            << " (clang++-14, libomp; per-item code compiled by clang), " << c.child->ready_line()
            << "; steals = chunks run off their static owner\n";
    }
  }
  a.child_note = child.str();
}

Analysis analyze(const Measured& m) {
  Analysis a;
  judge_rows(m, a);
  cost_spreads(m, a);
  summary_lines(m, a);
  return a;
}

// The table as the terminal and frontsteal.md show it: the serial loop first, then every scheduler and P,
// then the cells that could not run. Existing columns first, in their old order; the added ones (cpu, off-cpu,
// the two comparisons) after lock waits, audit last.
report::Table shown_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"}, {"scheduler", "scheduler", text}, {"frames_per_s", "frames/s"},
                   {"speedup", "speed-up"}, {"ideal_pct", "% of ideal"}, {"utilization_pct", "utilization"},
                   {"imbalance_mean", "imbalance"}, {"steals", "steals (failed)"}, {"lock_waits", "lock waits"},
                   {"cpu_pct", "cpu"}, {"off_cpu_pct", "off-cpu"}, {"ratio_vs_serial", "T_P/T1 [95% CI]", text},
                   {"verdict_vs_serial", "vs serial", text}, {"ratio_vs_queue", "T_P/T_queue [95% CI]", text},
                   {"verdict_vs_queue", "vs queue-mutex", text}, {"audit", "audit", text}});
  t.add_row({1, "serial loop (T1)", fixed(1000.0 * m.o.frames / a.t1_ms, 2), "1.00", "100.0", "-", "-", "-", "-", "-",
             "-", "reference", "-", "-", "-", "-"});
  for (const Row& r : a.rows) {
    const Cell& c = *r.cell;
    const std::uint64_t failed = c.totals.steal_attempts - c.totals.steals_succeeded;
    t.add_row({c.workers, c.scheduler, fixed(r.fps, 2), fixed(r.speedup, 2), fixed(r.ideal_pct, 1),
               fixed(r.utilization, 1) + "%", fixed(r.imbalance_mean, 3),
               std::to_string(c.totals.steals_succeeded) + " (" + std::to_string(failed) + ")", c.totals.lock_waits,
               fixed(r.cpu_pct, 1) + "%", fixed(r.off_cpu_pct, 1) + "%", r.vs_serial.interval_text(),
               r.vs_serial.verdict_text(), r.vs_queue ? r.vs_queue->interval_text() : "-",
               r.vs_queue ? r.vs_queue->verdict_text() : (c.scheduler == "queue-mutex" ? "reference" : "-"),
               c.failed() ? "FAILED" : "ok"});
  }
  for (const Cell& c : m.not_available) {
    t.add_row({c.workers, c.scheduler, "not available: " + c.unavailable, "-", "-", "-", "-", "-", "-", "-", "-", "-",
               "-", "-", "-", "-"});
  }
  return t;
}

// The data (frontsteal.csv, and each row of frontsteal.json's results[]): full precision, the serial loop first.
report::Table data_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"}, {"scheduler", "scheduler", text}, {"path_ms", "path (ms)"},
                   {"frames_per_s", "frames/s"}, {"speedup", "speed-up"}, {"ideal_pct", "% of ideal"},
                   {"utilization_pct", "utilization (%)"}, {"imbalance_mean", "imbalance"},
                   {"imbalance_max", "max imbalance"}, {"steals", "steals"}, {"steal_attempts", "steal attempts"},
                   {"lock_waits", "lock waits"}, {"lock_wait_ms", "lock wait (ms)"}, {"setup_ms", "set-up (ms)"},
                   {"audit_failures", "audit failures"}, {"triangle_mismatches", "triangle mismatches"},
                   {"tessellation_inconsistencies", "tessellation inconsistencies"}, {"cpu_pct", "cpu (%)"},
                   {"off_cpu_pct", "off-cpu (%)"}, {"path_spread_pct", "spread (%)"},
                   {"ratio_vs_serial", "T_P/T1"}, {"ratio_vs_serial_ci_low", "T_P/T1 low"},
                   {"ratio_vs_serial_ci_high", "T_P/T1 high"}, {"verdict_vs_serial", "vs serial", text},
                   {"effect_vs_serial_pct", "effect vs serial (%)"}, {"ratio_vs_queue", "T_P/T_queue"},
                   {"ratio_vs_queue_ci_low", "T_P/T_queue low"}, {"ratio_vs_queue_ci_high", "T_P/T_queue high"},
                   {"verdict_vs_queue", "vs queue-mutex", text}, {"effect_vs_queue_pct", "effect vs queue-mutex (%)"},
                   {"reliable", "reliable", text}});
  auto num = [](double v) { return report::Cell::fixed(v, 3); };
  const report::Cell none = report::Cell::empty();
  std::vector<report::Cell> serial{1, "serial", num(a.t1_ms), num(1000.0 * m.o.frames / a.t1_ms), 1, 100};
  serial.insert(serial.end(), 8, none);
  serial.insert(serial.end(), {0, 0, a.serial_inconsistencies, none, none, num(100 * a.serial_spread)});
  serial.insert(serial.end(), 10, none);
  serial.emplace_back(a.noise_warnings.empty());
  t.add_row(std::move(serial));
  auto comparison = [&](std::vector<report::Cell>& row, const ShownComparison* c) {
    if (!c) {
      row.insert(row.end(), 5, none);
      return;
    }
    row.insert(row.end(), {num(c->c.ratio.median), num(c->c.ratio.low), num(c->c.ratio.high),
                           c->reliable ? st::to_string(c->c.verdict) : "unreliable", num(c->c.effect_pct)});
  };
  for (const Row& r : a.rows) {
    const Cell& c = *r.cell;
    std::vector<report::Cell> row{c.workers, c.scheduler, num(r.path_ms), num(r.fps), num(r.speedup), num(r.ideal_pct),
                                  num(r.utilization), num(r.imbalance_mean), num(c.imbalance_max),
                                  c.totals.steals_succeeded, c.totals.steal_attempts, c.totals.lock_waits,
                                  num(c.totals.lock_wait_ns / 1e6), num(c.setup_ms), c.audit_failures,
                                  c.triangle_mismatches, c.tessellation_inconsistencies, num(r.cpu_pct),
                                  num(r.off_cpu_pct), num(r.spread_pct)};
    comparison(row, &r.vs_serial);
    comparison(row, r.vs_queue ? &*r.vs_queue : nullptr);
    row.emplace_back(r.vs_serial.reliable && (!r.vs_queue || r.vs_queue->reliable));
    t.add_row(std::move(row));
  }
  return t;
}

// frontsteal.json: the set-up, the round-robin spread, the noise, the serial loop, and per scheduler and P the
// data table's row with the structured values added (comparisons, noise, per worker, per repeat, per frame).
Json results_json(const Measured& m, const Analysis& a, const report::Table& data) {
  const Options& o = m.o;
  Json js = report::document(kProgram, kSchemaVersion, "measured", FRONTSTEAL_GIT_COMMIT);
  js["machine"] = a.machine;
  js["scene"] = o.scene;
  js["surfaces"] = m.wl.model.surfaces.size();
  js["frames"] = o.frames;
  js["repeats"] = o.repeats;
  js["tolerance_px"] = o.tolerance;
  js["image"] = {o.width, o.height};
  js["hardware_threads"] = m.cores;
  js["repeats_note"] = m.repeats_note;
  js["pinned"] = o.pin;
  js["path"] = ts::name(o.path);
  js["path_note"] = a.path_line;
  if (o.interference) {
    js["interference"] = {{"on", true}, {"duty_pct", 100 * o.interference->duty},
                          {"setup", o.interference->pinned ? "pinned" : "unpinned"}, {"period_ms", 10},
                          {"co_runner_cpu", m.co_runner_cpu}, {"co_runner_core_share_measured", a.co_runner_core_share},
                          {"serial_loop", "co-runner paused"}, {"note", a.interference_line}};
  } else {
    js["interference"] = {{"on", false}};
  }
  Json spreads = Json::array();
  for (const SpreadRow& r : a.spreads) {
    spreads.push_back({{"workers", r.p}, {"serial_item_times", spread_json(r.measured)},
                       {"estimates", spread_json(r.estimated)},
                       {"round_robin_busy", r.busy ? spread_json(*r.busy) : Json(nullptr)}});
  }
  js["round_robin_spread"] = spreads;
  js["noise"] = {{"before", usage_json(a.before_usage, o.noise)}, {"during", usage_json(a.during_usage, o.noise)},
                 {"after", usage_json(a.after_usage, o.noise)}, {"co_runner_share_during", a.during_usage.known_share()},
                 {"load1_before", m.at_start.load1}, {"load1_after", m.at_end.load1},
                 {"serial_spread_pct", 100 * a.serial_spread}, {"busy_threshold_pct", 100 * o.noise.other_share},
                 {"spread_threshold_pct", 100 * o.noise.spread}, {"verdicts", a.verdicts},
                 {"unreliable_verdicts", a.unreliable}, {"warnings", a.noise_warnings}};
  js["serial"] = {{"path_ms", a.t1_ms}, {"path_ms_per_repeat", m.serial_path_ms},
                  {"triangles_per_frame", m.wl.serial_triangles},
                  {"inconsistent_surfaces_per_frame", m.wl.serial_inconsistencies},
                  {"capped_surfaces_per_frame", m.wl.serial_capped}, {"max_steps", m.wl.settings.max_steps},
                  {"frame_ms_median", frame_medians(m.serial_frame_ms, o.frames)}};
  const Json rows = data.json();  // [0] is the serial loop, already under "serial"
  Json results = Json::array();
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const Row& r = a.rows[i];
    const Cell& c = *r.cell;
    Json row = rows.at(i + 1);
    row["items_stolen"] = c.totals.items_stolen;
    row["vs_serial"] = r.vs_serial.json();
    row["vs_queue_mutex"] = r.vs_queue ? r.vs_queue->json() : Json(nullptr);
    row["noise"] = usage_json(c.usage, o.noise);
    Json per_worker = Json::array();
    for (const fs::WorkerFrameStats& ws : c.per_worker) {
      per_worker.push_back({{"items", ws.items_processed}, {"busy_ms", ws.busy_ns / 1e6}, {"cpu_ms", ws.cpu_ns / 1e6},
                            {"active_ms", ws.active_ns / 1e6}});
    }
    row["per_worker"] = per_worker;
    row["path_ms_per_repeat"] = c.path_ms;
    row["frame_ms_median"] = frame_medians(c.frame_ms, o.frames);
    results.push_back(std::move(row));
  }
  js["results"] = results;
  Json not_available = Json::array();
  for (const Cell& c : m.not_available) {
    not_available.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"reason", c.unavailable}});
  }
  js["not_available"] = not_available;
  Json children = Json::array();
  for (const Cell& c : m.cells) {
    if (c.child) children.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"ready", c.child->ready_line()}});
  }
  js["child_processes"] = children;
  return js;
}

// A string for a gnuplot double-quoted literal: quotes and backslashes escaped, control characters dropped.
std::string gnuplot_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
}

// Plots: speed-up against P (one line per scheduler, the ideal dashed), and frame time along the path at the
// largest P not above the core count. The data and the script are always written; gnuplot runs unless --no-plot.
void write_plots(const Measured& m, const Analysis& a, const report::ResultsDir& dir) {
  const Options& o = m.o;
  std::ostringstream dat;
  for (const auto& name : o.schedulers) {
    dat << "\"" << name << "\"\n";
    for (const Row& r : a.rows) {
      if (r.cell->scheduler == name) dat << r.cell->workers << ' ' << r.speedup << '\n';
    }
    dat << "\n\n";
  }
  dir.write("frontsteal-speedup.dat", dat.str());
  fs::WorkerId best_p = 1;
  for (fs::WorkerId p : o.threads) {
    if (p <= m.cores) best_p = std::max(best_p, p);
  }
  std::ostringstream frames;
  auto block = [&](const std::string& title, const std::vector<std::vector<double>>& per_repeat) {
    frames << "\"" << title << "\"\n";
    const std::vector<double> med = frame_medians(per_repeat, o.frames);
    for (int f = 0; f < o.frames; ++f) frames << f << ' ' << med[f] << '\n';
    frames << "\n\n";
  };
  block("serial loop", m.serial_frame_ms);
  int blocks = 1;
  for (const Row& r : a.rows) {
    if (r.cell->workers != best_p) continue;
    block(r.cell->scheduler + " P=" + std::to_string(best_p), r.cell->frame_ms);
    ++blocks;
  }
  dir.write("frontsteal-frames.dat", frames.str());
  const fs::WorkerId max_p = *std::max_element(o.threads.begin(), o.threads.end());
  std::ostringstream gp;
  gp << "# gnuplot script written by frontsteal; run from " << o.out << ": gnuplot frontsteal.gp\n"
     << "set terminal pngcairo size 1200,760 font 'sans,10'\nset key outside right top\nset grid\n"
     << "set output 'frontsteal-speedup.png'\n"
     << "set title \"Tessellation speed-up over the serial loop (measured): " << gnuplot_text(o.scene) << ", "
     << m.wl.model.surfaces.size() << " surfaces\\n" << gnuplot_text(a.machine) << "\"\n"
     << "set xlabel 'workers P'\nset ylabel 'speed-up (T1 / T_P)'\nset xrange [0.5:" << max_p + 0.5 << "]\n"
     << "set yrange [0:*]\n"
     << "plot for [i=0:" << o.schedulers.size() - 1 << "] 'frontsteal-speedup.dat' index i using 1:2 with "
        "linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1), (x <= " << m.cores << " ? x : " << m.cores
     << ") with lines dashtype 2 lc 'black' title 'ideal'\n"
     << "set output 'frontsteal-frames.png'\n"
     << "set title 'Frame time along the camera path (measured), P = " << best_p
     << (o.path == ts::CameraPathKind::orbit_then_zoom
             ? " (frames 0-" + std::to_string(o.frames / 2 - 1) + " orbit, then zoom)"
             : std::string(" (path ") + ts::name(o.path) + ")")
     << (o.interference ? ", interference on" : "") << "'\n"
     << "set xlabel 'frame'\nset ylabel 'ms'\nset autoscale x\nset yrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1 << "] 'frontsteal-frames.dat' index i using 1:2 with linespoints "
        "lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)\n";
  dir.write("frontsteal.gp", gp.str());
  if (o.plot) dir.plot("frontsteal.gp");
}

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

// The table on stdout; frontsteal.{md,csv,json}, the plot data, script and PNGs in --out. Exit status of the run.
int write_results(const Measured& m, const Progress& progress) {
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
              << fixed(progress.seconds(), 0) << " s)\n";
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

}  // namespace

int main(int argc, char** argv) {
  Options o = parse(argc, argv);
  const unsigned cores = hardware_cores();
  // The noise monitor's "before" window runs from here to the first measured repeat (loading, warm-up,
  // scheduler set-up: our own work, so anything else that ran meanwhile was someone else's).
  const nz::ProcSample at_start = nz::sample_now();
  const fs::ThreadPinning pinning;
  // --interference: the co-runner (started after the warm-ups, reaped by this guard on every way out of main;
  // PR_SET_PDEATHSIG covers std::exit and being killed). Samples of the noise monitor read its CPU time.
  fi::CoRunner co_runner;
  auto sample = [&] { return nz::sample_now(co_runner.pid()); };

  // ---- the workload -------------------------------------------------------------------------------------
  Workload wl;
  const auto load_start = std::chrono::steady_clock::now();
  try {
    wl.model = ts::load_scene(o.scene, FRONTSTEAL_DATA_DIR);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": cannot load scene '" << o.scene << "': " << e.what() << '\n';
    return 2;
  }
  const auto n = static_cast<fs::ItemId>(wl.model.surfaces.size());
  if (n == 0) {
    std::cerr << kProgram << ": scene '" << o.scene << "' has no surfaces\n";
    return 2;
  }
  for (const ts::Surface& s : wl.model.surfaces) wl.prepared.push_back(ts::prepare_surface(s));
  wl.buffers.resize(n);
  wl.settings.pixel_tolerance = o.tolerance;
  wl.settings.planted_defect = o.planted_defect;
  const ts::Box box = ts::model_box(wl.model);
  const ts::DenseRegion dense = ts::densest_region(wl.model);
  for (int f = 0; f < o.frames; ++f) {
    // orbit-then-zoom is camera_on_path itself: the same views as before --path existed.
    wl.cameras.push_back(ts::camera_on(o.path, box, f, o.frames, o.width, o.height, &dense));
    wl.frusta.push_back(ts::Frustum::of(wl.cameras.back()));
  }
  // Hints for the spatial partitions: patch centres, and the cost estimate of the path's first (overview) view.
  sc::WorkloadHints hints;
  {
    const ts::TessellationSettings& st = wl.settings;
    for (const ts::PreparedSurface& p : wl.prepared) {
      const glm::dvec3 c = p.box.centre();
      hints.centres.push_back({c.x, c.y, c.z});
      const ts::SurfacePlan plan = ts::plan_surface(p, wl.cameras[0], wl.frusta[0], st);
      hints.costs.push_back(std::max(1.0, ts::estimate_cost(p, plan, st)));
    }
  }
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  if (!o.quiet) {
    std::fprintf(stderr, "frontsteal: scene %s: %u surfaces, %d frames (path %s), %s, %u hardware threads; "
                 "prepared in %.2f s\n", o.scene.c_str(), n, o.frames, ts::name(o.path), cpu_model().c_str(), cores,
                 load_s);
  }

  // Tessellates surface `id` for frame `f`, with worker w's scratch; returns its triangle count.
  std::vector<ts::TessellationScratch> scratch(
      std::max<std::size_t>(1, *std::max_element(o.threads.begin(), o.threads.end())));
  std::vector<std::uint32_t> triangles(n, 0);
  // Per surface, this frame: the tessellation's own audit (tiling, area, tracing: surface_tessellator.hpp,
  // step 6) failed, and the step cap held the deviation bound back.
  std::vector<std::uint8_t> inconsistent(n, 0), capped(n, 0);
  auto tessellate = [&](int f, fs::ItemId id, fs::WorkerId w) {
    const ts::SurfaceResult r = ts::tessellate_surface(wl.prepared[id], wl.cameras[f], wl.frusta[f], wl.settings,
                                                       scratch[w], wl.buffers[id]);
    triangles[id] = static_cast<std::uint32_t>(r.triangles);
    inconsistent[id] = r.inconsistencies() > 0;
    capped[id] = r.capped;
  };
  auto frame_triangles = [&] {
    std::uint64_t t = 0;
    for (auto x : triangles) t += x;
    return t;
  };
  auto frame_count = [](const std::vector<std::uint8_t>& flags) {
    return static_cast<std::uint64_t>(std::count(flags.begin(), flags.end(), std::uint8_t{1}));
  };
  auto first_inconsistent = [&] {
    const auto it = std::find(inconsistent.begin(), inconsistent.end(), std::uint8_t{1});
    return it == inconsistent.end() ? std::string() : wl.model.surfaces[static_cast<std::size_t>(it - inconsistent.begin())].name;
  };

  auto total_steps = [&] {
    return 1 + static_cast<std::size_t>(std::max(o.repeats, 1)) * (1 + o.threads.size() * o.schedulers.size());
  };
  Progress progress(o.quiet, total_steps());

  // ---- the serial reference (T1): a plain loop on this thread ---------------------------------------------
  std::vector<double> serial_path_ms;
  std::vector<std::vector<double>> serial_frame_ms;
  // Per frame and surface: the warm-up pass's measured time (ns) and the cost estimate, for the round-robin
  // cost spread (round_robin_spread.hpp).
  std::vector<std::vector<double>> item_ns(o.frames, std::vector<double>(n)), item_estimate(o.frames, std::vector<double>(n));
  for (int f = 0; f < o.frames; ++f) {
    for (fs::ItemId id = 0; id < n; ++id) {
      item_estimate[f][id] = ts::estimate_cost(wl.prepared[id], ts::plan_surface(wl.prepared[id], wl.cameras[f], wl.frusta[f], wl.settings), wl.settings);
    }
  }
  const auto warm_start = std::chrono::steady_clock::now();
  for (int f = 0; f < o.frames; ++f) {  // warm-up pass; also the reference triangle counts and per-item times
    for (fs::ItemId id = 0; id < n; ++id) {
      const auto t0 = std::chrono::steady_clock::now();
      tessellate(f, id, 0);
      item_ns[f][id] = static_cast<double>(
          std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
    }
    wl.serial_triangles.push_back(frame_triangles());
    wl.serial_inconsistencies.push_back(frame_count(inconsistent));
    wl.serial_capped.push_back(frame_count(capped));
    if (wl.serial_inconsistencies.back() > 0) {
      std::cerr << kProgram << ": frame " << f << ": " << wl.serial_inconsistencies.back()
                << " surfaces fail the tessellation audit (first: " << first_inconsistent() << ")\n";
    }
  }
  const double warm_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - warm_start).count();
  // --repeats auto: one round of repeats costs about T1 for the serial loop plus T1 / min(P, cores) per
  // scheduler and P (plus the 5 ms settling pause); the warm-up pass gives T1. Ten repeats when they fit in
  // the budget (the bootstrap interval of a median is informative from about ten pairs), else as many as
  // fit, but never fewer than 5, the count earlier results were measured with.
  std::string repeats_note = "set by --repeats";
  const bool auto_repeats = o.repeats == 0;
  if (auto_repeats) {
    double round_s = warm_s;
    for (fs::WorkerId p : o.threads) {
      round_s += o.schedulers.size() * (warm_s / std::min<double>(p, cores) + 0.005);
    }
    const int fit = static_cast<int>(o.budget_s / std::max(round_s, 1e-9));
    o.repeats = std::clamp(fit, 5, 10);
    repeats_note = "auto: ~" + fixed(round_s, 1) + " s per round predicted, budget " + fixed(o.budget_s, 0) + " s";
    progress.set_total(total_steps());
  }
  progress.step("serial warm-up pass (reference triangle counts); " + std::to_string(o.repeats) + " repeats (" +
                repeats_note + ")");

  // ---- the schedulers -----------------------------------------------------------------------------------
  std::vector<Cell> cells;
  for (fs::WorkerId p : o.threads) {
    for (const auto& name : o.schedulers) {
      Cell c;
      c.scheduler = name;
      c.workers = p;
      cells.push_back(std::move(c));
    }
  }
  fs::ExecutionCounter runs(n);

  std::vector<nz::Usage> serial_usage;  // per repeat: the machine while the serial loop ran
  auto run_serial_path = [&] {
    std::vector<double> per_frame;
    double total = 0;
    if (o.pin) pinning.pin_this_thread(0);
    co_runner.pause();  // T1 is the undisturbed reference (no-op without --interference)
    const nz::ProcSample before = sample();
    for (int f = 0; f < o.frames; ++f) {
      const auto t0 = std::chrono::steady_clock::now();
      for (fs::ItemId id = 0; id < n; ++id) tessellate(f, id, 0);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      per_frame.push_back(ms);
      total += ms;
    }
    serial_usage.push_back(nz::usage_between(before, sample()));
    co_runner.resume();
    if (o.pin) pinning.unpin_this_thread();
    serial_path_ms.push_back(total);
    serial_frame_ms.push_back(per_frame);
  };

  // The caller of oneTBB and OpenMP is their worker 0: under --pin it is pinned by its first item, and given
  // back every CPU after each path so the next scheduler's threads are not born confined to one core.
  auto unpin_caller = [&] {
    if (!o.pin) return;
    pinning.unpin_this_thread();
    t_pinned_as = -1;
  };
  // openmp-static-steal: the child runs the whole path (llvm_openmp_child.hpp); the same accounting and the
  // same audits, from what it reports. Its CPU time is ours, not another process's, for the noise monitor.
  auto run_child_path = [&](Cell& c) {
    std::vector<double> per_frame;
    double total = 0;
    const nz::ProcSample before = sample();
    const std::uint64_t child_ticks = c.child->cpu_ticks();
    const std::vector<sc::ChildFrame> frames = c.child->run_path();
    nz::Usage usage = nz::usage_between(before, sample());
    usage.self_ticks += c.child->cpu_ticks() - child_ticks;
    c.usage += usage;
    for (int f = 0; f < o.frames; ++f) {
      const sc::ChildFrame& cf = frames[static_cast<std::size_t>(f)];
      const fs::FrameStats& st = cf.stats;
      const double ms = static_cast<double>(st.wall_ns) / 1e6;
      per_frame.push_back(ms);
      total += ms;
      c.totals += st.totals();
      if (c.per_worker.size() < st.workers.size()) c.per_worker.resize(st.workers.size());
      for (std::size_t w = 0; w < st.workers.size(); ++w) c.per_worker[w] += st.workers[w];
      c.busy_over_available += static_cast<double>(st.totals().busy_ns);
      c.available += static_cast<double>(st.wall_ns) * st.workers.size();
      c.imbalance_sum += st.imbalance();
      c.imbalance_max = std::max(c.imbalance_max, st.imbalance());
      ++c.frames_run;
      const std::string at = "frame " + std::to_string(f) + ": ";
      if (!cf.audit.exactly_once()) {
        ++c.audit_failures;
        std::ostringstream m;
        m << at << cf.audit;
        if (c.first_problem.empty()) c.first_problem = m.str();
      }
      if (cf.inconsistent > 0) {
        c.tessellation_inconsistencies += cf.inconsistent;
        if (c.first_problem.empty()) c.first_problem = at + std::to_string(cf.inconsistent) + " surfaces fail the tessellation audit";
      }
      if (cf.triangles != wl.serial_triangles[static_cast<std::size_t>(f)]) {
        ++c.triangle_mismatches;
        if (c.first_problem.empty()) {
          c.first_problem = at + std::to_string(cf.triangles) + " triangles, serial loop made " +
                            std::to_string(wl.serial_triangles[static_cast<std::size_t>(f)]);
        }
      }
    }
    c.path_ms.push_back(total);
    c.frame_ms.push_back(per_frame);
  };
  auto run_cell_path = [&](Cell& c) {
    if (c.child) return run_child_path(c);
    std::vector<double> per_frame, ratios;
    double total = 0;
    const nz::ProcSample before = sample();
    for (int f = 0; f < o.frames; ++f) {
      auto item = [&](fs::ItemId id, fs::WorkerId w) {
        if (o.pin && t_pinned_as != static_cast<int>(w)) {
          pinning.pin_this_thread(w);
          t_pinned_as = static_cast<int>(w);
        }
        runs.record(id);
        tessellate(f, id, w);
      };
      const fs::FrameStats& st = c.instance->run_frame(item);
      const double ms = static_cast<double>(st.wall_ns) / 1e6;
      per_frame.push_back(ms);
      total += ms;
      c.totals += st.totals();
      if (c.per_worker.size() < st.workers.size()) c.per_worker.resize(st.workers.size());
      for (std::size_t w = 0; w < st.workers.size(); ++w) c.per_worker[w] += st.workers[w];
      c.busy_over_available += static_cast<double>(st.totals().busy_ns);
      c.available += static_cast<double>(st.wall_ns) * st.workers.size();
      {
        std::vector<double> busy;
        for (const auto& w : st.workers) busy.push_back(static_cast<double>(w.busy_ns));
        ratios.push_back(sc::load_ratio(busy));
      }
      c.imbalance_sum += st.imbalance();
      c.imbalance_max = std::max(c.imbalance_max, st.imbalance());
      ++c.frames_run;
      const fs::ExecutionAudit audit = runs.audit_and_reset();
      if (!audit.exactly_once()) {
        ++c.audit_failures;
        if (c.first_problem.empty()) {
          std::ostringstream s;
          s << "frame " << f << ": " << audit;
          c.first_problem = s.str();
        }
      }
      if (const std::uint64_t bad = frame_count(inconsistent); bad > 0) {
        c.tessellation_inconsistencies += bad;
        if (c.first_problem.empty()) {
          c.first_problem = "frame " + std::to_string(f) + ": " + std::to_string(bad) +
                            " surfaces fail the tessellation audit (first: " + first_inconsistent() + ")";
        }
      }
      if (frame_triangles() != wl.serial_triangles[f]) {
        ++c.triangle_mismatches;
        if (c.first_problem.empty()) {
          c.first_problem = "frame " + std::to_string(f) + ": " + std::to_string(frame_triangles()) +
                            " triangles, serial loop made " + std::to_string(wl.serial_triangles[f]);
        }
      }
    }
    c.usage += nz::usage_between(before, sample());
    unpin_caller();
    c.busy_ratio.push_back(std::move(ratios));
    c.path_ms.push_back(total);
    c.frame_ms.push_back(per_frame);
  };

  // Construct every cell's scheduler (static partitions computed here, timed), with one untimed warm-up frame.
  for (Cell& c : cells) {
    if (c.scheduler == sc::kLlvmOpenMpName) {  // a child process per P, started here and kept (it warms up itself)
      c.unavailable = sc::llvm_openmp_unavailable_reason();
      if (c.unavailable.empty()) {
        sc::ChildWorkload cw;
        cw.scene = o.scene;
        cw.frames = o.frames;
        cw.path = ts::name(o.path);
        cw.tolerance = o.tolerance;
        cw.width = o.width;
        cw.height = o.height;
        cw.grain = o.grain;
        cw.plant_defect = o.planted_defect == ts::PlantedDefect::drop_ear               ? "drop-ear"
                          : o.planted_defect == ts::PlantedDefect::bridge_to_first_copy ? "wave1-bridge"
                                                                                        : "";
        cw.pin = o.pin;
        const auto t0 = std::chrono::steady_clock::now();
        try {
          c.child = std::make_unique<sc::LlvmOpenMpChild>(c.workers, n, cw);
        } catch (const std::exception& e) {
          c.unavailable = e.what();
        }
        c.setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      }
      if (!c.unavailable.empty()) {
        std::cerr << kProgram << ": " << c.scheduler << " P=" << c.workers << " not available: " << c.unavailable << '\n';
      }
      continue;
    }
    const sc::SchedulerInfo* info = sc::find_scheduler(c.scheduler);
    sc::SchedulerConfig config{.workers = c.workers, .items = n, .grain = o.grain, .seed = o.seed};
    const auto t0 = std::chrono::steady_clock::now();
    try {
      c.instance = info->make(config, hints);
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": cannot start " << c.scheduler << " with P=" << c.workers << ": " << e.what() << '\n';
      return 1;
    }
    c.setup_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    auto warm = [&](fs::ItemId id, fs::WorkerId w) {
      if (o.pin && t_pinned_as != static_cast<int>(w)) {
        pinning.pin_this_thread(w);
        t_pinned_as = static_cast<int>(w);
      }
      tessellate(0, id, w);
    };
    c.instance->run_frame(warm);
    unpin_caller();
  }
  // Cells that could not start (openmp-static-steal without its child) are reported, not measured.
  std::vector<Cell> not_available;
  for (Cell& c : cells) {
    if (!c.unavailable.empty()) not_available.push_back(std::move(c));
  }
  std::erase_if(cells, [](const Cell& c) { return !c.unavailable.empty() || (!c.instance && !c.child); });
  if (o.interference) {
    try {
      co_runner = fi::CoRunner::start({.duty = o.interference->duty, .period_us = 10'000,
                                       .cpu = o.interference->pinned ? pinning.cpu_of(0) : -1});
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": cannot start the interference co-runner: " << e.what() << '\n';
      return 1;
    }
    if (!o.quiet) {
      std::fprintf(stderr, "frontsteal: interference on: co-runner pid %d, %s\n", static_cast<int>(co_runner.pid()),
                   o.interference->describe().c_str());
    }
  }
  const nz::ProcSample measure_start = sample();
  const auto rounds_start = std::chrono::steady_clock::now();

  for (int r = 0; r < o.repeats; ++r) {
    // --repeats auto was chosen from a warm-up on the machine as it was then; when others load it later, the
    // rounds slow down. Whole rounds only (every series keeps its pairs), never fewer than 5, and stop once
    // the budget is spent, so the default run stays bounded on a shared machine.
    if (auto_repeats && r >= 5 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - rounds_start).count() > o.budget_s) {
      repeats_note += "; stopped after " + std::to_string(r) + " of " + std::to_string(o.repeats) +
                      " rounds: the budget was spent";
      o.repeats = r;
      break;
    }
    run_serial_path();
    progress.step("repeat " + std::to_string(r + 1) + "/" + std::to_string(o.repeats) + " serial loop: " +
                  fixed(serial_path_ms.back(), 0) + " ms for the path");
    for (Cell& c : cells) {
      try {
        run_cell_path(c);
      } catch (const std::exception& e) {
        std::cerr << kProgram << ": " << c.scheduler << " P=" << c.workers << ": " << e.what() << '\n';
        return 1;
      }
      // Library runtimes spin a little after a parallel region; let them settle before the next scheduler.
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      progress.step("repeat " + std::to_string(r + 1) + "/" + std::to_string(o.repeats) + " P=" +
                    std::to_string(c.workers) + " " + c.scheduler + ": " + fixed(c.path_ms.back(), 0) + " ms (" +
                    fixed(1000.0 * o.frames / c.path_ms.back(), 1) + " frames/s)");
    }
  }

  // The noise monitor's "after" window: a short pause with nothing of ours running (before gnuplot, whose
  // CPU time would count as another process's).
  const nz::ProcSample measure_end = sample();
  co_runner.pause();
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  const nz::ProcSample at_end = sample();
  co_runner.stop();  // killed and reaped now: nothing of ours runs while the results are written

  const Measured measured{o, cores, wl, dense, item_ns, item_estimate, serial_path_ms, serial_frame_ms, serial_usage,
                          cells, not_available, at_start, measure_start, measure_end, at_end, repeats_note,
                          o.interference && o.interference->pinned ? pinning.cpu_of(0) : -1};
  return write_results(measured, progress);
}
