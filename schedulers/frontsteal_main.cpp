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
// through reporting/ (report::Table, report::ResultsDir, nlohmann JSON): schedulers/main_job_report.hpp.
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
#include "reporting/table.hpp"
#include "schedulers/interference.hpp"
#include "schedulers/llvm_openmp_child.hpp"
#include "schedulers/main_job_report.hpp"
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
using frontsteal::main_job::Cell;
using frontsteal::main_job::Measured;
using frontsteal::main_job::Options;
using frontsteal::main_job::Workload;

namespace {

using frontsteal::cpu_model;
using frontsteal::median;

constexpr const char* kProgram = "frontsteal";

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

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }


// The worker id this thread is pinned as under --pin (-1: not pinned). Pinning happens on a thread's first
// item of a frame rather than inside each scheduler, so it reaches the threads of oneTBB and OpenMP too,
// which we do not create.
thread_local int t_pinned_as = -1;

// The scene loaded and prepared, its camera path, and the hints for the spatial partitions (patch centres,
// and the cost estimate of the path's first, overview, view). Exits 2 when the scene cannot be loaded or is
// empty (before any measurement: nothing to clean up).
struct PreparedScene {
  Workload wl;
  ts::DenseRegion dense;
  sc::WorkloadHints hints;
};

PreparedScene prepare_scene(const Options& o, unsigned cores) {
  PreparedScene scene;
  Workload& wl = scene.wl;
  const auto load_start = std::chrono::steady_clock::now();
  try {
    wl.model = ts::load_scene(o.scene, FRONTSTEAL_DATA_DIR);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": cannot load scene '" << o.scene << "': " << e.what() << '\n';
    std::exit(2);
  }
  const auto n = static_cast<fs::ItemId>(wl.model.surfaces.size());
  if (n == 0) {
    std::cerr << kProgram << ": scene '" << o.scene << "' has no surfaces\n";
    std::exit(2);
  }
  for (const ts::Surface& s : wl.model.surfaces) wl.prepared.push_back(ts::prepare_surface(s));
  wl.buffers.resize(n);
  wl.settings.pixel_tolerance = o.tolerance;
  wl.settings.planted_defect = o.planted_defect;
  const ts::Box box = ts::model_box(wl.model);
  scene.dense = ts::densest_region(wl.model);
  for (int f = 0; f < o.frames; ++f) {
    // orbit-then-zoom is camera_on_path itself: the same views as before --path existed.
    wl.cameras.push_back(ts::camera_on(o.path, box, f, o.frames, o.width, o.height, &scene.dense));
    wl.frusta.push_back(ts::Frustum::of(wl.cameras.back()));
  }
  for (const ts::PreparedSurface& p : wl.prepared) {
    const glm::dvec3 c = p.box.centre();
    scene.hints.centres.push_back({c.x, c.y, c.z});
    const ts::SurfacePlan plan = ts::plan_surface(p, wl.cameras[0], wl.frusta[0], wl.settings);
    scene.hints.costs.push_back(std::max(1.0, ts::estimate_cost(p, plan, wl.settings)));
  }
  const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  if (!o.quiet) {
    std::fprintf(stderr, "frontsteal: scene %s: %u surfaces, %d frames (path %s), %s, %u hardware threads; "
                 "prepared in %.2f s\n", o.scene.c_str(), n, o.frames, ts::name(o.path), cpu_model().c_str(), cores,
                 load_s);
  }
  return scene;
}

// Tessellates surface `id` for frame `f` with worker w's scratch into the surface's own buffer, and keeps per
// surface what the audits need: its triangle count, whether the tessellation's own audit (tiling, area,
// tracing: surface_tessellator.hpp, step 6) failed, and whether the step cap held the deviation bound back.
class FrameTessellator {
 public:
  FrameTessellator(Workload& wl, fs::WorkerId max_workers)
      : wl_(wl), scratch_(std::max<std::size_t>(1, max_workers)), triangles_(wl.model.surfaces.size(), 0),
        inconsistent_(wl.model.surfaces.size(), 0), capped_(wl.model.surfaces.size(), 0) {}

  void run(int f, fs::ItemId id, fs::WorkerId w) {
    const ts::SurfaceResult r = ts::tessellate_surface(wl_.prepared[id], wl_.cameras[f], wl_.frusta[f], wl_.settings,
                                                       scratch_[w], wl_.buffers[id]);
    triangles_[id] = static_cast<std::uint32_t>(r.triangles);
    inconsistent_[id] = r.inconsistencies() > 0;
    capped_[id] = r.capped;
  }
  std::uint64_t frame_triangles() const {
    std::uint64_t t = 0;
    for (auto x : triangles_) t += x;
    return t;
  }
  std::uint64_t count_inconsistent() const { return count(inconsistent_); }
  std::uint64_t count_capped() const { return count(capped_); }
  std::string first_inconsistent() const {
    const auto it = std::find(inconsistent_.begin(), inconsistent_.end(), std::uint8_t{1});
    return it == inconsistent_.end() ? std::string()
                                     : wl_.model.surfaces[static_cast<std::size_t>(it - inconsistent_.begin())].name;
  }

 private:
  static std::uint64_t count(const std::vector<std::uint8_t>& flags) {
    return static_cast<std::uint64_t>(std::count(flags.begin(), flags.end(), std::uint8_t{1}));
  }
  Workload& wl_;
  std::vector<ts::TessellationScratch> scratch_;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint8_t> inconsistent_, capped_;
};

// The serial warm-up pass: the reference triangle counts (and audit counts) per frame into `wl`, and per frame
// and surface the measured time (ns) and the cost estimate, for the round-robin cost spread
// (round_robin_spread.hpp).
struct WarmUp {
  std::vector<std::vector<double>> item_ns, item_estimate;
  double seconds = 0;  // the pass's wall time: about T1
};

WarmUp warm_up(const Options& o, Workload& wl, FrameTessellator& tess) {
  const auto n = wl.model.surfaces.size();
  WarmUp w{std::vector<std::vector<double>>(o.frames, std::vector<double>(n)),
           std::vector<std::vector<double>>(o.frames, std::vector<double>(n)), 0};
  for (int f = 0; f < o.frames; ++f) {
    for (fs::ItemId id = 0; id < n; ++id) {
      w.item_estimate[f][id] = ts::estimate_cost(
          wl.prepared[id], ts::plan_surface(wl.prepared[id], wl.cameras[f], wl.frusta[f], wl.settings), wl.settings);
    }
  }
  const auto warm_start = std::chrono::steady_clock::now();
  for (int f = 0; f < o.frames; ++f) {
    for (fs::ItemId id = 0; id < n; ++id) {
      const auto t0 = std::chrono::steady_clock::now();
      tess.run(f, id, 0);
      w.item_ns[f][id] = static_cast<double>(
          std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
    }
    wl.serial_triangles.push_back(tess.frame_triangles());
    wl.serial_inconsistencies.push_back(tess.count_inconsistent());
    wl.serial_capped.push_back(tess.count_capped());
    if (wl.serial_inconsistencies.back() > 0) {
      std::cerr << kProgram << ": frame " << f << ": " << wl.serial_inconsistencies.back()
                << " surfaces fail the tessellation audit (first: " << tess.first_inconsistent() << ")\n";
    }
  }
  w.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - warm_start).count();
  return w;
}

// --repeats auto: one round of repeats costs about T1 for the serial loop plus T1 / min(P, cores) per
// scheduler and P (plus the 5 ms settling pause); the warm-up pass gives T1. Ten repeats when they fit in
// the budget (the bootstrap interval of a median is informative from about ten pairs), else as many as
// fit, but never fewer than 5, the count earlier results were measured with. Sets o.repeats; returns the note.
std::string choose_repeats(Options& o, double warm_s, unsigned cores) {
  double round_s = warm_s;
  for (fs::WorkerId p : o.threads) {
    round_s += o.schedulers.size() * (warm_s / std::min<double>(p, cores) + 0.005);
  }
  const int fit = static_cast<int>(o.budget_s / std::max(round_s, 1e-9));
  o.repeats = std::clamp(fit, 5, 10);
  return "auto: ~" + fixed(round_s, 1) + " s per round predicted, budget " + fixed(o.budget_s, 0) + " s";
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
  PreparedScene scene = prepare_scene(o, cores);
  Workload& wl = scene.wl;
  const ts::DenseRegion& dense = scene.dense;
  const sc::WorkloadHints& hints = scene.hints;
  const auto n = static_cast<fs::ItemId>(wl.model.surfaces.size());

  FrameTessellator tess(wl, *std::max_element(o.threads.begin(), o.threads.end()));

  auto total_steps = [&] {
    return 1 + static_cast<std::size_t>(std::max(o.repeats, 1)) * (1 + o.threads.size() * o.schedulers.size());
  };
  Progress progress(o.quiet, total_steps());

  // ---- the serial reference (T1): a plain loop on this thread ---------------------------------------------
  std::vector<double> serial_path_ms;
  std::vector<std::vector<double>> serial_frame_ms;
  const WarmUp warm = warm_up(o, wl, tess);
  const std::vector<std::vector<double>>& item_ns = warm.item_ns;
  const std::vector<std::vector<double>>& item_estimate = warm.item_estimate;
  const bool auto_repeats = o.repeats == 0;
  std::string repeats_note = "set by --repeats";
  if (auto_repeats) {
    repeats_note = choose_repeats(o, warm.seconds, cores);
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
      for (fs::ItemId id = 0; id < n; ++id) tess.run(f, id, 0);
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
        tess.run(f, id, w);
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
      if (const std::uint64_t bad = tess.count_inconsistent(); bad > 0) {
        c.tessellation_inconsistencies += bad;
        if (c.first_problem.empty()) {
          c.first_problem = "frame " + std::to_string(f) + ": " + std::to_string(bad) +
                            " surfaces fail the tessellation audit (first: " + tess.first_inconsistent() + ")";
        }
      }
      if (tess.frame_triangles() != wl.serial_triangles[f]) {
        ++c.triangle_mismatches;
        if (c.first_problem.empty()) {
          c.first_problem = "frame " + std::to_string(f) + ": " + std::to_string(tess.frame_triangles()) +
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
      tess.run(0, id, w);
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
  return write_results(measured, progress.seconds());
}
