// frontsteal — the main job: every scheduler on the real tessellation workload, side by side.
//
// A scene (default: the generated 15,906-surface plant, the size of the paper's largest Fig. 8 model) is
// tessellated along a deterministic camera path — half an orbit of the whole model, half a zoom into a small
// corner region, where round robin becomes badly imbalanced (paper §3) — by a serial loop (T1) and by every
// scheduler at P = 1 … cores and oversubscribed. Repeats are interleaved (repeat r of every scheduler runs
// before repeat r+1 of any), so slow drifts of a noisy machine spread over all of them. Every frame is
// audited: each surface ran exactly once, the frame's triangle count equals the serial loop's, and every
// surface passed the tessellation's own audit (trimmed pieces tiled exactly, area equal to the trim loops').
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/cli_args.hpp"
#include "core/execution_counter.hpp"
#include "core/machine_info.hpp"
#include "core/paired_comparison.hpp"
#include "core/thread_pinning.hpp"
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

namespace {

using frontsteal::cpu_model;
using frontsteal::median;

constexpr std::string_view kProgram = "frontsteal";

[[noreturn]] void usage_error(const std::string& message) { fs::cli::usage_error(kProgram, message); }

template <class T>
T parse_number(std::string_view flag, std::string_view text, T min_value, T max_value) {
  return fs::cli::parse_number<T>(kProgram, flag, text, min_value, max_value);
}

constexpr std::string_view kUsage = R"(usage: frontsteal [options]

Tessellates a scene along a deterministic camera path (an orbit of the whole model, then a zoom into a small
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
equal to the trim loops'). Any failure is reported and the exit status is 1.

options:
  --scene S         teapot | teacup | teaspoon | plant:N[:seed] | path to a model file  (default plant:15906)
  --schedulers L    comma-separated scheduler names, or all                 (default all; see --list)
  --threads L       comma-separated worker counts P          (default 1..cores, then 2 x cores)
  --path K          camera path: orbit-then-zoom (half an orbit of the whole model, half a zoom into a
                    corner), walkthrough (low among the parts, corner to corner), dense-zoom (from the
                    overview to a close view of the densest region: a few surfaces' view-dependent cost
                    dominates)                                                 (default orbit-then-zoom)
  --frames F        frames along the path                                            (default 24)
  --repeats R|auto  interleaved runs of the path per scheduler and P; medians, paired ratios and their
                    bootstrap intervals are reported. auto: 10 when the warm-up pass predicts they fit in
                    --budget, else as many as fit, at least 5; rounds stop early (not below 5) once
                    the budget is spent                                                 (default auto)
  --budget S        seconds the measured repeats may take under --repeats auto         (default 180)
  --pin             pin worker w (and the serial loop, as worker 0) to the w-th allowed CPU (off by default;
                    the "spread of the repeats" line says whether it narrows them)
  --interference DUTY[,pinned|unpinned]
                    a co-runner child process busy-loops DUTY % (1-100, default 50) of each 10 ms on one
                    core while the schedulers run (it is paused while the serial loop runs, so T1 stays the
                    undisturbed reference). pinned: workers pinned as with --pin and the co-runner on worker
                    0's core (the asymmetric slowdown static lists cannot absorb); unpinned (default): nothing
                    pinned, the OS places everything. Always killed and reaped at the end (and if frontsteal
                    dies); its CPU time is reported apart and is not counted as noise          (default off)
  --noise-busy PCT  share of the machine other processes (or steal) may take before a run is unreliable
                    (default 10)
  --noise-spread PCT  spread max/min - 1 of the serial loop's repeats above which a run is unreliable
                    (default 5)
  --tolerance PX    screen-space tolerance in pixels                                 (default 1)
  --grain G         items per claim of the chunked schedulers (queue, counter, Chase-Lev, TBB, OpenMP)
                    (default: each scheduler's own: N/(100P) for queue and counter, 1 for the others)
  --size WxH        image size the steps are computed for                     (default 1280x720)
  --seed S          seed of victim orders and of the annealing                        (default 1)
  --out DIR         results directory                                               (default out)
  --no-plot         do not run gnuplot (the .gp scripts are still written)
  --plant-defect D  negative control: tessellate with a planted defect (wave1-bridge | drop-ear) to see
                    the audit fail (exit 1)
  --list            list the schedulers and exit
  --quiet           no progress lines
  --help            this text

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
)";

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

Options parse(int argc, char** argv) {
  Options o;
  fs::cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--list") {
      for (const auto& s : sc::scheduler_registry()) {
        std::cout << std::left << std::setw(22) << s.name << s.summary
                  << (s.contract == fs::Contract::kAtLeastOnce ? "  [at-least-once: not run on tessellation]" : "")
                  << '\n';
      }
      std::cout << std::left << std::setw(22) << sc::kLlvmOpenMpName << sc::kLlvmOpenMpSummary
                << (sc::llvm_openmp_unavailable_reason().empty() ? "" : "  [not available: " + sc::llvm_openmp_unavailable_reason() + "]")
                << '\n';
      std::exit(0);
    } else if (a == "--scene") {
      o.scene = args.value();
    } else if (a == "--schedulers") {
      o.schedulers = fs::cli::split_list(args.value());
    } else if (a == "--threads") {
      o.threads.clear();
      for (const auto& t : fs::cli::split_list(args.value())) {
        o.threads.push_back(parse_number<fs::WorkerId>("--threads", t, 1, 1024));
      }
    } else if (a == "--frames") {
      o.frames = parse_number<int>(a, args.value(), 1, 100000);
    } else if (a == "--path") {
      const std::string_view v = args.value();
      const auto k = ts::camera_path_named(v);
      if (!k || (*k != ts::CameraPathKind::orbit_then_zoom && *k != ts::CameraPathKind::walkthrough &&
                 *k != ts::CameraPathKind::dense_zoom)) {
        usage_error("--path expects orbit-then-zoom, walkthrough or dense-zoom, got '" + std::string(v) + "'");
      }
      o.path = *k;
    } else if (a == "--interference") {
      std::string why;
      o.interference = fi::parse_interference(args.value(), &why);
      if (!o.interference) usage_error("--interference expects DUTY[,pinned|unpinned]: " + why);
    } else if (a == "--repeats") {
      const std::string_view v = args.value();
      o.repeats = v == "auto" ? 0 : parse_number<int>(a, v, 1, 1000);
    } else if (a == "--budget") {
      o.budget_s = parse_number<double>(a, args.value(), 1.0, 1e6);
    } else if (a == "--pin") {
      o.pin = true;
    } else if (a == "--noise-busy") {
      o.noise.other_share = o.noise.steal_share = parse_number<double>(a, args.value(), 0.0, 100.0) / 100.0;
    } else if (a == "--noise-spread") {
      o.noise.spread = parse_number<double>(a, args.value(), 0.0, 1000.0) / 100.0;
    } else if (a == "--tolerance") {
      o.tolerance = parse_number<double>(a, args.value(), 0.01, 1000.0);
    } else if (a == "--grain") {
      o.grain = parse_number<fs::ItemId>(a, args.value(), 1, std::numeric_limits<fs::ItemId>::max());
    } else if (a == "--size") {
      const std::string v(args.value());
      const auto x = v.find('x');
      if (x == std::string::npos) usage_error("--size expects WxH, e.g. 1280x720, got '" + v + "'");
      o.width = parse_number<int>("--size", std::string_view(v).substr(0, x), 16, 16384);
      o.height = parse_number<int>("--size", std::string_view(v).substr(x + 1), 16, 16384);
    } else if (a == "--seed") {
      o.seed = parse_number<std::uint64_t>(a, args.value(), 0, std::numeric_limits<std::uint64_t>::max());
    } else if (a == "--out") {
      o.out = args.value();
    } else if (a == "--no-plot") {
      o.plot = false;
    } else if (a == "--plant-defect") {
      const std::string_view d = args.value();
      const auto defect = ts::planted_defect_named(d);
      if (!defect) usage_error("--plant-defect expects wave1-bridge or drop-ear, got '" + std::string(d) + "'");
      o.planted_defect = *defect;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      usage_error("unknown option '" + std::string(a) + "'");
    }
  }
  if (o.interference && o.interference->pinned) o.pin = true;  // pinned set-up: workers pinned as by --pin
  if (o.threads.empty()) {
    for (unsigned p = 1; p <= hardware_cores(); ++p) o.threads.push_back(p);
    o.threads.push_back(2 * hardware_cores());
  }
  std::vector<std::string> wanted;
  if (o.schedulers.empty() || (o.schedulers.size() == 1 && o.schedulers[0] == "all")) {
    for (const auto& s : sc::scheduler_registry()) {
      if (s.contract == fs::Contract::kExactlyOnce) wanted.push_back(s.name);
    }
    wanted.emplace_back(sc::kLlvmOpenMpName);  // a child process (llvm_openmp_child.hpp); "not available" if not built
  } else {
    for (const auto& name : o.schedulers) {
      if (name == sc::kLlvmOpenMpName) {
        wanted.push_back(name);
        continue;
      }
      const sc::SchedulerInfo* s = sc::find_scheduler(name);
      if (!s) usage_error("unknown scheduler '" + name + "' (see --list)");
      if (s->contract != fs::Contract::kExactlyOnce) {
        usage_error(name + " is at-least-once: a duplicated surface would be tessellated into its buffer by two "
                           "threads at once; the main job runs exactly-once schedulers only");
      }
      wanted.push_back(name);
    }
  }
  o.schedulers = wanted;
  return o;
}


std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
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
  std::string json() const {
    std::ostringstream j;
    j << std::setprecision(6) << "{\"ratio_median\": " << c.ratio.median << ", \"ci95_low\": " << c.ratio.low
      << ", \"ci95_high\": " << c.ratio.high << ", \"pairs\": " << c.pairs << ", \"effect_pct\": " << c.effect_pct
      << ", \"verdict\": \"" << (reliable ? st::to_string(c.verdict) : "unreliable") << "\", \"verdict_if_reliable\": \""
      << st::to_string(c.verdict) << "\", \"reliable\": " << (reliable ? "true" : "false") << "}";
    return j.str();
  }
};

std::string usage_json(const nz::Usage& u, const nz::Thresholds& t) {
  std::ostringstream j;
  j << std::setprecision(4) << "{\"wall_s\": " << u.wall_s << ", \"windows\": " << u.windows << ", \"ticks\": "
    << u.total_ticks << ", \"other_share\": " << u.other_share() << ", \"steal_share\": " << u.steal_share()
    << ", \"busy\": " << (nz::assess(u, t).busy ? "true" : "false") << "}";
  return j.str();
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

  // ---- results ------------------------------------------------------------------------------------------
  const double t1_ms = median(serial_path_ms);

  // Noise: the machine before (loading and warm-up), during (every measured path, added up) and after; and
  // the spread of the serial loop's repeats. Each makes every verdict unreliable; a busy machine during one
  // cell's paths (or its reference's) makes that comparison unreliable.
  const nz::Usage before_usage = nz::usage_between(at_start, measure_start);
  const nz::Usage during_usage = nz::usage_between(measure_start, measure_end);
  const nz::Usage after_usage = nz::usage_between(measure_end, at_end);
  nz::Usage serial_total;
  for (const nz::Usage& u : serial_usage) serial_total += u;
  const double serial_spread = nz::spread_of(serial_path_ms);
  std::vector<std::string> noise_warnings;  // run-wide reasons: every verdict is unreliable
  if (const auto a = nz::assess(before_usage, o.noise); a.busy) noise_warnings.push_back("before the measurement: " + a.reason);
  if (const auto a = nz::assess(during_usage, o.noise); a.busy) noise_warnings.push_back("during the measurement: " + a.reason);
  if (const auto a = nz::assess(after_usage, o.noise); a.busy) noise_warnings.push_back("after the measurement: " + a.reason);
  if (serial_spread > o.noise.spread) {
    noise_warnings.push_back("the serial loop's repeats spread by " + fixed(100 * serial_spread, 1) +
                             " % (max/min - 1; threshold " + fixed(100 * o.noise.spread, 1) + " %)");
  }
  auto judge = [&](const std::vector<double>& candidate, const std::vector<double>& reference, nz::Usage usage) {
    ShownComparison sc_;
    sc_.c = st::compare_paired(candidate, reference);
    const nz::Assessment a = nz::assess(usage, o.noise);
    if (!noise_warnings.empty() || a.busy) {
      sc_.reliable = false;
      sc_.noise_reason = a.busy ? a.reason : noise_warnings.front();
    }
    return sc_;
  };
  const Cell* no_cell = nullptr;
  auto queue_cell = [&](fs::WorkerId p) {
    for (const Cell& q : cells) {
      if (q.scheduler == "queue-mutex" && q.workers == p) return &q;
    }
    return no_cell;
  };

  struct Row {
    const Cell* cell = nullptr;
    double path_ms = 0, fps = 0, speedup = 0, ideal_pct = 0, utilization = 0, imbalance_mean = 0;
    double cpu_pct = 0, off_cpu_pct = 0, spread_pct = 0;
    ShownComparison vs_serial;
    std::optional<ShownComparison> vs_queue;  // absent for queue-mutex itself, or when it was not run
  };
  std::vector<Row> rows;
  bool problems = false;
  std::size_t verdicts = 0, unreliable = 0;
  for (const Cell& c : cells) {
    Row row{};
    row.cell = &c;
    row.path_ms = median(c.path_ms);
    row.fps = 1000.0 * o.frames / row.path_ms;
    row.speedup = t1_ms / row.path_ms;
    const double ideal_ms = t1_ms / std::min<double>(c.workers, cores);
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
    row.vs_serial = judge(c.path_ms, serial_path_ms, with_serial);
    ++verdicts;
    if (!row.vs_serial.reliable) ++unreliable;
    if (const Cell* q = queue_cell(c.workers); q && q != &c) {
      nz::Usage with_queue = c.usage;
      with_queue += q->usage;
      row.vs_queue = judge(c.path_ms, q->path_ms, with_queue);
      ++verdicts;
      if (!row.vs_queue->reliable) ++unreliable;
    }
    rows.push_back(row);
    if (c.failed()) problems = true;
  }
  std::vector<double> cell_spreads;
  for (const Row& r : rows) cell_spreads.push_back(r.spread_pct);
  std::ostringstream spread_line;
  spread_line << "spread of the repeats (max/min - 1): serial loop " << fixed(100 * serial_spread, 1)
              << " %; schedulers: median " << fixed(median(cell_spreads), 1) << " %, max "
              << fixed(cell_spreads.empty() ? 0.0 : *std::max_element(cell_spreads.begin(), cell_spreads.end()), 1)
              << " % (workers pinned: " << (o.pin ? "yes, --pin" : "no") << ")";
  std::ostringstream noise_line;
  noise_line << "noise monitor: other processes / steal, as a share of the machine: before "
             << fixed(100 * before_usage.other_share(), 1) << " / " << fixed(100 * before_usage.steal_share(), 1)
             << " %, during " << fixed(100 * during_usage.other_share(), 1) << " / "
             << fixed(100 * during_usage.steal_share(), 1) << " %, after " << fixed(100 * after_usage.other_share(), 1)
             << " / " << fixed(100 * after_usage.steal_share(), 1) << " %; load average " << fixed(at_start.load1, 2)
             << " before, " << fixed(at_end.load1, 2) << " after (thresholds: " << fixed(100 * o.noise.other_share, 0)
             << " % busy, " << fixed(100 * o.noise.spread, 0) << " % spread)";
  // The workload's set-up: the camera path, the round-robin cost spread per P, the interference.
  std::ostringstream path_line;
  path_line << "camera path: " << ts::name(o.path);
  if (o.path == ts::CameraPathKind::dense_zoom) {
    const glm::dvec3 c = dense.box.centre();
    path_line << " (ends at the densest region: " << dense.surfaces << " surfaces centred in one grid cell of edge "
              << fixed(dense.cell_edge, 2) << " (the median control-box diagonal), around (" << fixed(c.x, 1) << ", "
              << fixed(c.y, 1) << ", " << fixed(c.z, 1) << "), box diagonal "
              << fixed(glm::length(dense.box.hi - dense.box.lo), 2) << ")";
  }
  {
    // How much a few surfaces dominate: the 16 costliest surfaces' share of a frame's estimated cost.
    double top_max = 0;
    int top_frame = 0;
    for (int f = 0; f < o.frames; ++f) {
      std::vector<double> c = item_estimate[f];
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
    path_line << "; the 16 costliest surfaces carry up to " << fixed(100 * top_max, 1)
              << " % of a frame's estimated cost (frame " << top_frame << ")";
  }
  struct SpreadRow {
    fs::WorkerId p;
    sc::CostSpread measured, estimated;
    std::optional<sc::CostSpread> busy;  // from the round-robin row, when it ran at this P
  };
  std::vector<SpreadRow> spreads;
  for (fs::WorkerId p : o.threads) {
    if (p < 2) continue;
    SpreadRow r{p, sc::round_robin_spread(item_ns, p), sc::round_robin_spread(item_estimate, p), std::nullopt};
    for (const Cell& c : cells) {
      if (c.scheduler != "round-robin" || c.workers != p || c.busy_ratio.empty()) continue;
      std::vector<double> per_frame;  // median over repeats, per frame
      for (int f = 0; f < o.frames; ++f) {
        std::vector<double> v;
        for (const auto& rep : c.busy_ratio) v.push_back(rep[f]);
        per_frame.push_back(median(v));
      }
      r.busy = sc::summarize_spread(std::move(per_frame));
    }
    spreads.push_back(std::move(r));
  }
  using sc::ratio_text;
  std::ostringstream spread_summary;
  spread_summary << "round-robin cost spread (max/min over workers of the per-frame cost, item i on worker i mod P; "
                    "worst frame / median over frames; paper §3: 1:50 for static schemes):";
  if (spreads.empty()) spread_summary << " no P >= 2 was run";
  for (const SpreadRow& r : spreads) {
    spread_summary << "\n  P=" << r.p << ": serial loop's measured per-item times dealt round robin "
                   << ratio_text(r.measured.worst) << " (frame " << r.measured.worst_frame << ") / "
                   << ratio_text(r.measured.median) << "; cost estimates " << ratio_text(r.estimated.worst) << " / "
                   << ratio_text(r.estimated.median) << "; round-robin row's busy time "
                   << (r.busy ? ratio_text(r.busy->worst) + " / " + ratio_text(r.busy->median) : std::string("not run"));
  }
  nz::Usage cells_usage;
  for (const Cell& c : cells) cells_usage += c.usage;
  const double ticks_per_s = static_cast<double>(sysconf(_SC_CLK_TCK));
  const double co_runner_core_share =
      cells_usage.wall_s > 0 ? static_cast<double>(cells_usage.known_ticks) / (cells_usage.wall_s * ticks_per_s) : 0;
  std::ostringstream interference_line;
  if (o.interference) {
    interference_line << "interference: ON, a co-runner child process busy-looping " << o.interference->describe()
                      << ", during every scheduler row (paused during the serial loop: T1 is undisturbed); it used "
                      << fixed(100 * co_runner_core_share, 1) << " % of one core while the schedulers ran "
                      << "(its own CPU time from /proc/<pid>/stat, reported here and not counted as noise)";
  } else {
    interference_line << "interference: off";
  }

  std::ostringstream warning;
  if (unreliable > 0) {
    warning << "WARNING: noisy machine: " << unreliable << " of " << verdicts
            << " verdicts are marked unreliable. Reasons:\n";
    for (const auto& w : noise_warnings) warning << "  - " << w << "\n";
    std::size_t cell_flags = 0;
    for (const Row& r : rows) {
      if (!r.vs_serial.reliable && r.vs_serial.noise_reason != (noise_warnings.empty() ? "" : noise_warnings.front())) {
        if (cell_flags++ < 5) {
          warning << "  - while " << r.cell->scheduler << " P=" << r.cell->workers << " or its reference ran: "
                  << r.vs_serial.noise_reason << "\n";
        }
      }
    }
    if (cell_flags > 5) warning << "  - ... and " << cell_flags - 5 << " more scheduler/P cells\n";
    warning << "Re-run on a quiet machine before drawing conclusions from these verdicts.\n";
  }
  std::uint64_t serial_inconsistencies = 0, capped_total = 0, capped_max = 0;
  for (int f = 0; f < o.frames; ++f) {
    serial_inconsistencies += wl.serial_inconsistencies[f];
    capped_total += wl.serial_capped[f];
    capped_max = std::max(capped_max, wl.serial_capped[f]);
  }
  if (serial_inconsistencies > 0) problems = true;
  // One line that says what "audit ok" covers, and what it found.
  std::ostringstream tessellation_audit;
  tessellation_audit << "tessellation audit (every surface of every frame, every run: trimmed pieces tiled exactly, "
                        "(u, v) area = trim-loop area): "
                     << serial_inconsistencies << " inconsistencies in the serial loop; surfaces held at the "
                     << wl.settings.max_steps << "-step cap (deviation may exceed " << o.tolerance << " px there): "
                     << capped_total << " surface-frames, at most " << capped_max << " per frame";

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) {
    std::cerr << kProgram << ": cannot create " << o.out << ": " << ec.message() << '\n';
    return 1;
  }
  const std::filesystem::path dir(o.out);
  const std::string machine = cpu_model() + ", " + std::to_string(cores) + " hardware threads";

  // Table (stdout and markdown).
  std::ostringstream table;
  // Existing columns first, in their old order; the added ones (cpu, off-cpu, the two comparisons) after
  // lock waits, audit last.
  table << "| P | scheduler | frames/s | speed-up | % of ideal | utilization | imbalance | steals (failed) | lock waits "
           "| cpu | off-cpu | T_P/T1 [95% CI] | vs serial | T_P/T_queue [95% CI] | vs queue-mutex | audit |\n"
        << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|---|\n";
  table << "| 1 | serial loop (T1) | " << fixed(1000.0 * o.frames / t1_ms, 2)
        << " | 1.00 | 100.0 | - | - | - | - | - | - | reference | - | - | - | - |\n";
  for (const Row& r : rows) {
    const Cell& c = *r.cell;
    const std::uint64_t failed = c.totals.steal_attempts - c.totals.steals_succeeded;
    table << "| " << c.workers << " | " << c.scheduler << " | " << fixed(r.fps, 2) << " | " << fixed(r.speedup, 2)
          << " | " << fixed(r.ideal_pct, 1) << " | " << fixed(r.utilization, 1) << "% | " << fixed(r.imbalance_mean, 3)
          << " | " << c.totals.steals_succeeded << " (" << failed << ") | " << c.totals.lock_waits << " | "
          << fixed(r.cpu_pct, 1) << "% | " << fixed(r.off_cpu_pct, 1) << "% | " << r.vs_serial.interval_text() << " | "
          << r.vs_serial.verdict_text() << " | "
          << (r.vs_queue ? r.vs_queue->interval_text() : "-") << " | "
          << (r.vs_queue ? r.vs_queue->verdict_text() : (c.scheduler == "queue-mutex" ? "reference" : "-")) << " | "
          << (c.failed() ? "FAILED" : "ok") << " |\n";
  }
  for (const Cell& c : not_available) {
    table << "| " << c.workers << " | " << c.scheduler << " | not available: " << c.unavailable
          << " | - | - | - | - | - | - | - | - | - | - | - | - | - |\n";
  }
  std::ostringstream child_note;  // how openmp-static-steal ran, and the proof that static_steal was in effect
  for (const Cell& c : cells) {
    if (c.child) {
      child_note << sc::kLlvmOpenMpName << " P=" << c.workers << ": child process " << sc::llvm_openmp_child_path()
                 << " (clang++-14, libomp; per-item code compiled by clang), " << c.child->ready_line()
                 << "; steals = chunks run off their static owner\n";
    }
  }
  std::cout << "\nfrontsteal: " << o.scene << ", " << n << " surfaces, " << o.frames << " frames x " << o.repeats
            << " repeats (medians), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height << "\n"
            << "machine: " << machine << " (measured, not simulated)\n"
            << "ideal = T1 / min(P, " << cores << "); utilization = busy / (wall x P), summed over every frame; "
            << "imbalance = max/mean busy per frame, averaged; cpu, off-cpu = workers' thread CPU time and time "
            << "in the frame without a CPU, over wall x P\n"
            << "repeats: " << o.repeats << " (" << repeats_note << "); T_P/T_ref = median of per-repeat ratios, "
            << "95 % bootstrap interval; verdict at 95 %, effect = change in path time\n"
            << path_line.str() << "\n" << interference_line.str() << "\n" << spread_summary.str() << "\n\n"
            << table.str() << '\n' << child_note.str() << tessellation_audit.str() << '\n' << spread_line.str() << '\n'
            << noise_line.str() << '\n';

  {
    std::ofstream md(dir / "frontsteal.md");
    md << "# frontsteal main job (measured)\n\n"
       << "Scene `" << o.scene << "` (" << n << " surfaces), " << o.frames << " frames along the camera path `"
       << ts::name(o.path) << "`, " << o.repeats << " interleaved repeats (medians), tolerance " << o.tolerance << " px, "
       << o.width << "x" << o.height << ". Machine: " << machine << ". Commit " << FRONTSTEAL_GIT_COMMIT << ".\n\n"
       << "Verdicts: median of the per-repeat ratios T_P[r] / T_ref[r] with its 95 % bootstrap interval; ahead / "
       << "behind when the interval lies below / above 1; effect = change in path time. cpu and off-cpu: the "
       << "workers' thread CPU time and their time in the frame without a CPU, over wall x P.\n\n"
       << "**" << path_line.str() << "; " << interference_line.str() << ".**\n\n```\n" << spread_summary.str()
       << "\n```\n\n" << table.str() << '\n' << child_note.str() << (child_note.str().empty() ? "" : "\n")
       << tessellation_audit.str() << ".\n\n" << spread_line.str() << ".\n\n"
       << noise_line.str() << ".\n";
    if (unreliable > 0) md << "\n**" << warning.str().substr(0, warning.str().find('\n')) << "**\n\n```\n" << warning.str() << "```\n";
  }
  {
    std::ofstream csv(dir / "frontsteal.csv");
    csv << "workers,scheduler,path_ms,frames_per_s,speedup,ideal_pct,utilization_pct,imbalance_mean,imbalance_max,"
           "steals,steal_attempts,lock_waits,lock_wait_ms,setup_ms,audit_failures,triangle_mismatches,"
           "tessellation_inconsistencies,cpu_pct,off_cpu_pct,path_spread_pct,ratio_vs_serial,ratio_vs_serial_ci_low,"
           "ratio_vs_serial_ci_high,verdict_vs_serial,effect_vs_serial_pct,ratio_vs_queue,ratio_vs_queue_ci_low,"
           "ratio_vs_queue_ci_high,verdict_vs_queue,effect_vs_queue_pct,reliable\n";
    csv << "1,serial," << t1_ms << ',' << 1000.0 * o.frames / t1_ms << ",1,100,,,,,,,,,0,0," << serial_inconsistencies
        << ",,," << 100 * serial_spread << ",,,,,,,,,,," << (noise_warnings.empty() ? "true" : "false") << "\n";
    for (const Row& r : rows) {
      const Cell& c = *r.cell;
      csv << c.workers << ',' << c.scheduler << ',' << r.path_ms << ',' << r.fps << ',' << r.speedup << ','
          << r.ideal_pct << ',' << r.utilization << ',' << r.imbalance_mean << ',' << c.imbalance_max << ','
          << c.totals.steals_succeeded << ',' << c.totals.steal_attempts << ',' << c.totals.lock_waits << ','
          << c.totals.lock_wait_ns / 1e6 << ',' << c.setup_ms << ',' << c.audit_failures << ','
          << c.triangle_mismatches << ',' << c.tessellation_inconsistencies << ',' << r.cpu_pct << ','
          << r.off_cpu_pct << ',' << r.spread_pct << ',' << r.vs_serial.c.ratio.median << ','
          << r.vs_serial.c.ratio.low << ',' << r.vs_serial.c.ratio.high << ",\""
          << (r.vs_serial.reliable ? st::to_string(r.vs_serial.c.verdict) : "unreliable") << "\","
          << r.vs_serial.c.effect_pct << ',';
      if (r.vs_queue) {
        csv << r.vs_queue->c.ratio.median << ',' << r.vs_queue->c.ratio.low << ',' << r.vs_queue->c.ratio.high << ",\""
            << (r.vs_queue->reliable ? st::to_string(r.vs_queue->c.verdict) : "unreliable") << "\","
            << r.vs_queue->c.effect_pct << ',';
      } else {
        csv << ",,,,,";
      }
      csv << ((r.vs_serial.reliable && (!r.vs_queue || r.vs_queue->reliable)) ? "true" : "false") << '\n';
    }
  }
  {
    std::ofstream js(dir / "frontsteal.json");
    js << std::setprecision(6);
    js << "{\n  \"kind\": \"measured\",\n  \"machine\": \"" << json_escape(machine) << "\",\n  \"commit\": \""
       << FRONTSTEAL_GIT_COMMIT << "\",\n  \"scene\": \"" << json_escape(o.scene) << "\",\n  \"surfaces\": " << n
       << ",\n  \"frames\": " << o.frames << ",\n  \"repeats\": " << o.repeats << ",\n  \"tolerance_px\": "
       << o.tolerance << ",\n  \"image\": [" << o.width << ", " << o.height << "],\n  \"hardware_threads\": " << cores
       << ",\n  \"repeats_note\": \"" << json_escape(repeats_note) << "\",\n  \"pinned\": " << (o.pin ? "true" : "false")
       << ",\n  \"path\": \"" << ts::name(o.path) << "\", \"path_note\": \"" << json_escape(path_line.str()) << "\""
       << ",\n  \"interference\": ";
    if (o.interference) {
      js << "{\"on\": true, \"duty_pct\": " << 100 * o.interference->duty << ", \"setup\": \""
         << (o.interference->pinned ? "pinned" : "unpinned") << "\", \"period_ms\": 10, \"co_runner_cpu\": "
         << (o.interference->pinned ? pinning.cpu_of(0) : -1) << ", \"co_runner_core_share_measured\": "
         << co_runner_core_share << ", \"serial_loop\": \"co-runner paused\", \"note\": \""
         << json_escape(interference_line.str()) << "\"}";
    } else {
      js << "{\"on\": false}";
    }
    js << ",\n  \"round_robin_spread\": [";
    for (std::size_t i = 0; i < spreads.size(); ++i) {
      const SpreadRow& r = spreads[i];
      js << (i ? ",\n    " : "\n    ") << "{\"workers\": " << r.p << ", \"serial_item_times\": " << sc::to_json(r.measured)
         << ", \"estimates\": " << sc::to_json(r.estimated) << ", \"round_robin_busy\": "
         << (r.busy ? sc::to_json(*r.busy) : std::string("null")) << "}";
    }
    js << "]";
    js
       << ",\n  \"noise\": {\"before\": " << usage_json(before_usage, o.noise) << ",\n            \"during\": "
       << usage_json(during_usage, o.noise) << ",\n            \"after\": " << usage_json(after_usage, o.noise)
       << ",\n            \"co_runner_share_during\": " << during_usage.known_share()
       << ",\n            \"load1_before\": " << at_start.load1 << ", \"load1_after\": " << at_end.load1
       << ", \"serial_spread_pct\": " << 100 * serial_spread << ", \"busy_threshold_pct\": "
       << 100 * o.noise.other_share << ", \"spread_threshold_pct\": " << 100 * o.noise.spread
       << ", \"verdicts\": " << verdicts << ", \"unreliable_verdicts\": " << unreliable << ", \"warnings\": [";
    for (std::size_t i = 0; i < noise_warnings.size(); ++i) js << (i ? ", " : "") << '"' << json_escape(noise_warnings[i]) << '"';
    js << "]}"
       << ",\n  \"serial\": {\"path_ms\": " << t1_ms << ", \"path_ms_per_repeat\": [";
    for (std::size_t k = 0; k < serial_path_ms.size(); ++k) js << (k ? ", " : "") << serial_path_ms[k];
    js << "], \"triangles_per_frame\": [";
    for (std::size_t f = 0; f < wl.serial_triangles.size(); ++f) js << (f ? ", " : "") << wl.serial_triangles[f];
    js << "], \"inconsistent_surfaces_per_frame\": [";
    for (std::size_t f = 0; f < wl.serial_inconsistencies.size(); ++f) js << (f ? ", " : "") << wl.serial_inconsistencies[f];
    js << "], \"capped_surfaces_per_frame\": [";
    for (std::size_t f = 0; f < wl.serial_capped.size(); ++f) js << (f ? ", " : "") << wl.serial_capped[f];
    js << "], \"max_steps\": " << wl.settings.max_steps << ", \"frame_ms_median\": [";
    for (int f = 0; f < o.frames; ++f) {
      std::vector<double> v;
      for (const auto& rep : serial_frame_ms) v.push_back(rep[f]);
      js << (f ? ", " : "") << median(v);
    }
    js << "]},\n  \"results\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      const Cell& c = *r.cell;
      js << "    {\"scheduler\": \"" << c.scheduler << "\", \"workers\": " << c.workers << ", \"path_ms\": "
         << r.path_ms << ", \"frames_per_s\": " << r.fps << ", \"speedup\": " << r.speedup << ", \"ideal_pct\": "
         << r.ideal_pct << ", \"utilization_pct\": " << r.utilization << ", \"imbalance_mean\": " << r.imbalance_mean
         << ", \"imbalance_max\": " << c.imbalance_max << ", \"steals\": " << c.totals.steals_succeeded
         << ", \"steal_attempts\": " << c.totals.steal_attempts << ", \"items_stolen\": " << c.totals.items_stolen
         << ", \"lock_waits\": " << c.totals.lock_waits << ", \"lock_wait_ms\": " << c.totals.lock_wait_ns / 1e6
         << ", \"setup_ms\": " << c.setup_ms << ", \"audit_failures\": " << c.audit_failures
         << ", \"triangle_mismatches\": " << c.triangle_mismatches << ", \"tessellation_inconsistencies\": "
         << c.tessellation_inconsistencies << ", \"cpu_pct\": " << r.cpu_pct << ", \"off_cpu_pct\": " << r.off_cpu_pct
         << ", \"path_spread_pct\": " << r.spread_pct << ", \"vs_serial\": " << r.vs_serial.json()
         << ", \"vs_queue_mutex\": " << (r.vs_queue ? r.vs_queue->json() : std::string("null"))
         << ", \"noise\": " << usage_json(c.usage, o.noise) << ", \"per_worker\": [";
      for (std::size_t w = 0; w < c.per_worker.size(); ++w) {
        const fs::WorkerFrameStats& ws = c.per_worker[w];
        js << (w ? ", " : "") << "{\"items\": " << ws.items_processed << ", \"busy_ms\": " << ws.busy_ns / 1e6
           << ", \"cpu_ms\": " << ws.cpu_ns / 1e6 << ", \"active_ms\": " << ws.active_ns / 1e6 << "}";
      }
      js << "], \"path_ms_per_repeat\": [";
      for (std::size_t k = 0; k < c.path_ms.size(); ++k) js << (k ? ", " : "") << c.path_ms[k];
      js << "], \"frame_ms_median\": [";
      for (int f = 0; f < o.frames; ++f) {
        std::vector<double> v;
        for (const auto& rep : c.frame_ms) v.push_back(rep[f]);
        js << (f ? ", " : "") << median(v);
      }
      js << "]}" << (i + 1 < rows.size() ? "," : "") << "\n";
    }
    js << "  ],\n  \"not_available\": [";
    for (std::size_t i = 0; i < not_available.size(); ++i) {
      js << (i ? ", " : "") << "{\"scheduler\": \"" << not_available[i].scheduler << "\", \"workers\": "
         << not_available[i].workers << ", \"reason\": \"" << json_escape(not_available[i].unavailable) << "\"}";
    }
    js << "],\n  \"child_processes\": [";
    bool first_child = true;
    for (const Cell& c : cells) {
      if (!c.child) continue;
      js << (first_child ? "" : ", ") << "{\"scheduler\": \"" << c.scheduler << "\", \"workers\": " << c.workers
         << ", \"ready\": \"" << json_escape(c.child->ready_line()) << "\"}";
      first_child = false;
    }
    js << "]\n}\n";
  }

  // Plots: speed-up against P (one line per scheduler, the ideal dashed), and frame time along the path at the
  // largest P not above the core count.
  {
    std::ofstream dat(dir / "frontsteal-speedup.dat");
    for (const auto& name : o.schedulers) {
      dat << "\"" << name << "\"\n";
      for (const Row& r : rows) {
        if (r.cell->scheduler == name) dat << r.cell->workers << ' ' << r.speedup << '\n';
      }
      dat << "\n\n";
    }
    fs::WorkerId best_p = 1;
    for (fs::WorkerId p : o.threads) {
      if (p <= cores) best_p = std::max(best_p, p);
    }
    std::ofstream frames(dir / "frontsteal-frames.dat");
    frames << "\"serial loop\"\n";
    for (int f = 0; f < o.frames; ++f) {
      std::vector<double> v;
      for (const auto& rep : serial_frame_ms) v.push_back(rep[f]);
      frames << f << ' ' << median(v) << '\n';
    }
    frames << "\n\n";
    int blocks = 1;
    for (const Row& r : rows) {
      if (r.cell->workers != best_p) continue;
      frames << "\"" << r.cell->scheduler << " P=" << best_p << "\"\n";
      for (int f = 0; f < o.frames; ++f) {
        std::vector<double> v;
        for (const auto& rep : r.cell->frame_ms) v.push_back(rep[f]);
        frames << f << ' ' << median(v) << '\n';
      }
      frames << "\n\n";
      ++blocks;
    }
    const fs::WorkerId max_p = *std::max_element(o.threads.begin(), o.threads.end());
    std::ofstream gp(dir / "frontsteal.gp");
    gp << "# gnuplot script written by frontsteal; run from " << o.out << ": gnuplot frontsteal.gp\n"
       << "set terminal pngcairo size 1200,760 font 'sans,10'\nset key outside right top\nset grid\n"
       << "set output 'frontsteal-speedup.png'\n"
       << "set title \"Tessellation speed-up over the serial loop (measured): " << json_escape(o.scene) << ", " << n
       << " surfaces\\n" << json_escape(machine) << "\"\n"
       << "set xlabel 'workers P'\nset ylabel 'speed-up (T1 / T_P)'\nset xrange [0.5:" << max_p + 0.5 << "]\n"
       << "set yrange [0:*]\n"
       << "plot for [i=0:" << o.schedulers.size() - 1 << "] 'frontsteal-speedup.dat' index i using 1:2 with "
          "linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1), (x <= " << cores << " ? x : " << cores
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
  }
  if (o.plot) {
    const std::string command = "cd '" + o.out + "' && gnuplot frontsteal.gp";
    if (std::system(command.c_str()) != 0) {
      std::cerr << kProgram << ": gnuplot failed or is not installed (Debian: apt-get install gnuplot-nox); the data "
                   "and the script are in " << o.out << "/\n";
    }
  }
  std::cout << "\nwrote " << (dir / "frontsteal.json").string() << ", .csv, .md"
            << (o.plot ? ", frontsteal-speedup.png, frontsteal-frames.png" : "") << " (" << fixed(progress.seconds(), 0)
            << " s)\n";
  if (unreliable > 0) {
    // Last, on stdout and stderr, so it is the thing one sees.
    std::cout << '\n' << warning.str();
    std::cerr << kProgram << ": WARNING: noisy machine: " << unreliable << " of " << verdicts
              << " verdicts unreliable (reasons on stdout and in frontsteal.md)\n";
  }

  if (problems) {
    std::cerr << kProgram << ": AUDIT FAILED:\n";
    if (serial_inconsistencies > 0) {
      std::cerr << "  serial loop: " << serial_inconsistencies << " surface-frames fail the tessellation audit\n";
    }
    for (const Cell& c : cells) {
      if (c.failed()) {
        std::cerr << "  " << c.scheduler << " P=" << c.workers << ": " << c.audit_failures << " frames not exactly-once, "
                  << c.triangle_mismatches << " triangle mismatches, " << c.tessellation_inconsistencies
                  << " surface-frames failing the tessellation audit; first: " << c.first_problem << '\n';
      }
    }
    return 1;
  }
  return 0;
}
