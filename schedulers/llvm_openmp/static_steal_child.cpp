// static_steal_child.cpp — frontsteal-llvm-openmp: the tessellation workload under LLVM libomp's static_steal,
// in a process of its own, driven by the main job (schedulers/llvm_openmp_child.hpp) over pipes.
//
// Why a separate process: the main job links libgomp (openmp-dynamic) and two OpenMP runtimes must not share
// one. This file is compiled by clang++-14 with -fopenmp (libomp) and links the same g++-built tessellation
// library as the main job (schedulers/llvm_openmp/CMakeLists.txt says why that is safe).
//
// WHICH SCHEDULE, AND HOW WE KNOW: the loop is `schedule(runtime)`, and the run-sched-var comes from the
// environment, OMP_SCHEDULE=static_steal,1, which libomp reads when it is loaded, before main. So the child
// sets it and re-executes itself once (/proc/self/exe; the pid, the socket and the parent-death signal stay).
// No in-process spelling works in libomp 14: the kmp_sched_static_steal kind (102) passed to omp_set_schedule
// aborts in kmp_dispatch.cpp ("unknown scheduling type"), omp_set_schedule(omp_sched_dynamic) gives monotonic
// dynamic (a shared counter), and kmp_set_defaults("OMP_SCHEDULE=static_steal") after start-up changes what
// KMP_SETTINGS prints but not the loops (measured with the probe below: no steal).
// static_steal (kmp_dispatch.cpp): thread t owns the contiguous chunk range starting at t * (K / P) +
// min(t, K % P) of the K chunks, takes from its front, and a thief takes from a victim's back.
// omp_get_schedule cannot report it (libomp 14 maps it to "dynamic"), so the child PROVES it with a probe before it says ready, a loop of 64 P
// iterations in which
//   (a) each thread, at its first iteration, waits until every thread has taken its first one: under static
//       ranges (static or static_steal) thread t's first iteration is the start of its own range, since no
//       one can steal from a thread that is blocked in its first item; under a shared counter
//       (--schedule monotonic-dynamic) thread 1's first is 1;
//   (b) then thread 0 stays in its first iteration until some iteration has run on a thread other than its
//       static owner: under static_steal the others finish their ranges and steal from thread 0; under plain
//       static (--schedule static) nothing ever does, and the probe fails after 10 s.
// Both are deterministic (a forced interleaving, no timing luck); only a thread that does not arrive at all
// within 10 s in (a) makes the probe repeat (up to 5 times). During frames, "steals" are chunks run by a
// thread other than their static owner (same formula). With P = 1 there is nothing to prove (and libomp
// uses no ranges); with fewer chunks than threads libomp falls back to another schedule and steals are 0.
//
// PROTOCOL (one line each way; the parent writes, the child answers):
//   start-up          the child prepares the scene and cameras, proves the schedule, runs frame 0 once
//                     untimed, and prints  "ready items=N workers=P chunk=C chunks=K schedule=static-steal
//                     probe=confirmed:<attempts>"  or  "error <reason>"  (exit 1).
//   "path"            runs every frame of the path, one line per frame:
//                       frame <f> <wall_ns> <triangles> <inconsistent> <P> {<items> <busy_ns> <active_ns>
//                       <cpu_ns> <chunks_stolen> <items_stolen>} x P <runs>
//                     with <runs> the per-item execution counts of the frame, run-length encoded as
//                     "count*length,count*length,..." (all ones: "1*N"); then, once libomp's threads
//                     have stopped spinning (KMP_BLOCKTIME + 20 ms), "end".
//   "quit" or EOF     exit 0. The child also dies with its parent (PR_SET_PDEATHSIG, set by the parent).
// The parent audits: exactly once from <runs>, triangles against its own serial loop.
// --fault drop:K | dup:K  (negative controls) skip item K in every frame, or run it twice: the parent must
// catch either.
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/cli_args.hpp"
#include "core/thread_cpu_time.hpp"
#include "core/thread_pinning.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"

#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif

namespace ts = frontsteal::tess;
namespace cli = frontsteal::cli;

namespace {

constexpr std::string_view kProgram = "frontsteal-llvm-openmp";
constexpr std::string_view kUsage = R"(usage: frontsteal-llvm-openmp --workers P [options]

The tessellation workload under LLVM libomp's static_steal, for the main job (frontsteal), which starts it
as a child process and talks to it over stdin/stdout (protocol in schedulers/llvm_openmp/static_steal_child.cpp).
Commands on stdin: "path" (run the camera path once, report every frame), "quit".

options:
  --workers P        OpenMP threads (required)
  --scene S          as frontsteal's --scene                                       (default plant:15906)
  --frames F         frames along the path                                          (default 24)
  --path NAME        orbit-then-zoom | orbit | zoom | walkthrough | dense-zoom                (default orbit-then-zoom)
  --tolerance PX     screen-space tolerance in pixels                               (default 1)
  --size WxH         image size                                                     (default 1280x720)
  --grain G          items per chunk                                                (default 1)
  --plant-defect D   wave1-bridge | drop-ear (frontsteal's tessellation negative control)
  --pin              pin thread t to the t-th allowed CPU
  --schedule S       static-steal | monotonic-dynamic | static (the last two: the probe's negative
                     controls, which must make it fail)                               (default static-steal)
  --fault F          drop:K | dup:K: skip item K, or run it twice, in every frame (the audit's negative control)
  --help             this text
)";

struct Options {
  int workers = 0;
  std::string scene = "plant:15906";
  int frames = 24;
  ts::CameraPathKind path = ts::CameraPathKind::orbit_then_zoom;
  double tolerance = 1.0;
  int width = 1280, height = 720;
  int grain = 1;
  ts::PlantedDefect defect = ts::PlantedDefect::none;
  bool pin = false;
  std::string schedule = "static-steal";
  enum class Fault { none, drop, dup } fault = Fault::none;
  int fault_item = -1;
};

Options parse(int argc, char** argv) {
  Options o;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--workers") {
      o.workers = cli::parse_number<int>(kProgram, a, args.value(), 1, 1024);
    } else if (a == "--scene") {
      o.scene = args.value();
    } else if (a == "--frames") {
      o.frames = cli::parse_number<int>(kProgram, a, args.value(), 1, 100000);
    } else if (a == "--path") {
      const std::string_view v = args.value();
      bool found = false;
      for (auto k : {ts::CameraPathKind::orbit_then_zoom, ts::CameraPathKind::orbit, ts::CameraPathKind::zoom,
                     ts::CameraPathKind::walkthrough, ts::CameraPathKind::dense_zoom}) {
        if (v == ts::name(k)) o.path = k, found = true;
      }
      if (!found) cli::usage_error(kProgram, "--path: unknown path '" + std::string(v) + "'");
    } else if (a == "--tolerance") {
      o.tolerance = cli::parse_number<double>(kProgram, a, args.value(), 0.01, 1000.0);
    } else if (a == "--size") {
      const std::string v(args.value());
      const auto x = v.find('x');
      if (x == std::string::npos) cli::usage_error(kProgram, "--size expects WxH, got '" + v + "'");
      o.width = cli::parse_number<int>(kProgram, "--size", std::string_view(v).substr(0, x), 16, 16384);
      o.height = cli::parse_number<int>(kProgram, "--size", std::string_view(v).substr(x + 1), 16, 16384);
    } else if (a == "--grain") {
      o.grain = cli::parse_number<int>(kProgram, a, args.value(), 1, 1 << 30);
    } else if (a == "--plant-defect") {
      const auto d = ts::planted_defect_named(args.value());
      if (!d) cli::usage_error(kProgram, "--plant-defect expects wave1-bridge or drop-ear");
      o.defect = *d;
    } else if (a == "--pin") {
      o.pin = true;
    } else if (a == "--schedule") {
      const std::string_view v = args.value();
      if (v != "static-steal" && v != "monotonic-dynamic" && v != "static") {
        cli::usage_error(kProgram, "--schedule expects static-steal, monotonic-dynamic or static");
      }
      o.schedule = v;
    } else if (a == "--fault") {
      const std::string v(args.value());
      const auto colon = v.find(':');
      const std::string kind = v.substr(0, colon);
      if (colon == std::string::npos || (kind != "drop" && kind != "dup")) {
        cli::usage_error(kProgram, "--fault expects drop:K or dup:K, got '" + v + "'");
      }
      o.fault = kind == "drop" ? Options::Fault::drop : Options::Fault::dup;
      o.fault_item = cli::parse_number<int>(kProgram, "--fault", std::string_view(v).substr(colon + 1), 0, 1 << 30);
    } else {
      cli::usage_error(kProgram, "unknown option '" + std::string(a) + "'");
    }
  }
  if (o.workers == 0) cli::usage_error(kProgram, "--workers is required");
  return o;
}

using Clock = std::chrono::steady_clock;
std::int64_t ns_since(Clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t).count();
}

// The first chunk of thread t's static range in libomp's static_steal (kmp_dispatch.cpp).
long long range_start(long long t, long long chunks, long long threads) {
  const long long small = chunks / threads, extras = chunks % threads;
  return t * small + std::min(t, extras);
}
// The static owner of chunk c (the inverse of range_start).
int owner_of(long long c, long long chunks, long long threads) {
  int t = static_cast<int>(std::min(threads - 1, c / std::max(1LL, chunks / threads)));
  while (t > 0 && range_start(t, chunks, threads) > c) --t;
  while (t + 1 < threads && range_start(t + 1, chunks, threads) <= c) ++t;
  return t;
}

// The probe of the header. Returns the attempts it took, or 0 when static_steal was not observed.
int probe_static_steal(int threads) {
  if (threads == 1) return 1;  // one thread: nothing to tell apart
  const long long m = 64LL * threads;
  for (int attempt = 1; attempt <= 5; ++attempt) {
    std::vector<long long> first(static_cast<std::size_t>(threads), -1);
    std::atomic<int> arrived{0};
    std::atomic<bool> absent{false}, stolen{false}, no_steal{false};
#pragma omp parallel num_threads(threads)
    {
      const int t = omp_get_thread_num();
#pragma omp for schedule(runtime) nowait
      for (int i = 0; i < static_cast<int>(m); ++i) {  // 32-bit, as the frames' loop
        if (owner_of(i, m, threads) != t) stolen = true;
        if (first[static_cast<std::size_t>(t)] >= 0) continue;
        first[static_cast<std::size_t>(t)] = i;
        arrived.fetch_add(1);
        auto deadline = Clock::now() + std::chrono::seconds(10);
        while (arrived.load() < threads) {  // (a)
          if (Clock::now() > deadline) {
            absent = true;
            break;
          }
          std::this_thread::yield();
        }
        deadline = Clock::now() + std::chrono::seconds(10);
        while (t == 0 && !absent && !stolen) {  // (b)
          if (Clock::now() > deadline) {
            no_steal = true;
            break;
          }
          std::this_thread::yield();
        }
      }
    }
    if (absent) continue;
    bool ranges = true;
    for (int t = 0; t < threads; ++t) ranges = ranges && first[static_cast<std::size_t>(t)] == range_start(t, m, threads);
    return ranges && stolen && !no_steal ? attempt : 0;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  // The schedule of every schedule(runtime) loop below: libomp reads it from the environment when it is
  // loaded, so set it and start again (once; see the header).
  const char* want = o.schedule == "static-steal"        ? "static_steal,1"
                     : o.schedule == "monotonic-dynamic" ? "monotonic:dynamic,1"
                                                         : "static";
  if (const char* have = std::getenv("OMP_SCHEDULE"); !have || std::string_view(have) != want) {
    if (std::getenv("FRONTSTEAL_LLVM_OPENMP_REEXEC")) {
      std::cout << "error OMP_SCHEDULE=" << want << " did not survive re-execution" << std::endl;
      return 1;
    }
    ::setenv("OMP_SCHEDULE", want, 1);
    ::setenv("FRONTSTEAL_LLVM_OPENMP_REEXEC", "1", 1);
    ::execv("/proc/self/exe", argv);
    std::cout << "error cannot re-execute /proc/self/exe: " << std::strerror(errno) << std::endl;
    return 1;
  }
  const int P = o.workers;

  // ---- the workload, exactly as the main job prepares it ----------------------------------------------------
  ts::Model model;
  try {
    model = ts::load_scene(o.scene, FRONTSTEAL_DATA_DIR);
  } catch (const std::exception& e) {
    std::cout << "error cannot load scene '" << o.scene << "': " << e.what() << std::endl;
    return 1;
  }
  const auto n = static_cast<long long>(model.surfaces.size());
  std::vector<ts::PreparedSurface> prepared;
  for (const ts::Surface& s : model.surfaces) prepared.push_back(ts::prepare_surface(s));
  std::vector<ts::TriangleBuffers> buffers(static_cast<std::size_t>(n));
  ts::TessellationSettings settings;
  settings.pixel_tolerance = o.tolerance;
  settings.planted_defect = o.defect;
  const ts::Box box = ts::model_box(model);
  const ts::DenseRegion dense = ts::densest_region(model);  // dense-zoom's target, as the parent computes it
  std::vector<ts::Camera> cameras;
  std::vector<ts::Frustum> frusta;
  for (int f = 0; f < o.frames; ++f) {
    cameras.push_back(ts::camera_on(o.path, box, f, o.frames, o.width, o.height, &dense));
    frusta.push_back(ts::Frustum::of(cameras.back()));
  }
  std::vector<ts::TessellationScratch> scratch(static_cast<std::size_t>(P));
  std::vector<std::uint32_t> triangles(static_cast<std::size_t>(n), 0);
  std::vector<std::uint8_t> inconsistent(static_cast<std::size_t>(n), 0);
  std::vector<std::atomic<std::uint32_t>> runs(static_cast<std::size_t>(n));
  std::vector<std::int32_t> runner(static_cast<std::size_t>(n), -1);  // the thread that last ran item i
  const frontsteal::ThreadPinning pinning;

  const int attempts = probe_static_steal(P);
  if (attempts == 0) {
    std::cout << "error static_steal not in effect: the probe did not see every thread start at its static range "
                 "and then steal (schedule requested: " << o.schedule << ")" << std::endl;
    return 1;
  }

  const long long grain = o.grain;
  const long long chunks = (n + grain - 1) / grain;
  const bool static_ranges = P > 1 && chunks >= P;  // libomp's own condition for static_steal's ranges
  if (chunks > std::numeric_limits<int>::max()) {
    std::cout << "error " << chunks << " chunks: more than a 32-bit loop counts (use --grain)" << std::endl;
    return 1;
  }
  const int chunks32 = static_cast<int>(chunks);
  struct alignas(64) Worker {
    std::int64_t items = 0, busy_ns = 0, active_ns = 0, cpu_ns = 0, chunks_stolen = 0, items_stolen = 0;
  };
  std::vector<Worker> workers(static_cast<std::size_t>(P));

  auto run_item = [&](int f, long long id, int t) {
    const ts::SurfaceResult r = ts::tessellate_surface(prepared[id], cameras[f], frusta[f], settings,
                                                       scratch[t], buffers[id]);
    triangles[id] = static_cast<std::uint32_t>(r.triangles);
    inconsistent[id] = r.inconsistencies() > 0;
    runs[id].fetch_add(1, std::memory_order_relaxed);  // read after the region's end (its barrier orders it)
    runner[id] = t;
    ++workers[t].items;
  };
  // One frame; returns its wall time. Each chunk index c covers items [c * grain, min((c + 1) * grain, N)),
  // so static_steal's chunk 1 over chunk indices is its chunk `grain` over items, timed once per claim.
  auto run_frame = [&](int f) {
    for (auto& w : workers) w = Worker{};
    const Clock::time_point start = Clock::now();
#pragma omp parallel num_threads(P)
    {
      const int t = omp_get_thread_num();
      if (o.pin) pinning.pin_this_thread(static_cast<unsigned>(t));
      const Clock::time_point span = Clock::now();
      const std::int64_t cpu = frontsteal::thread_cpu_ns();
      // A 32-bit induction variable: libomp's lock-free static_steal (one 64-bit CAS on a thread's (count,
      // limit) pair); 64-bit ones take a per-thread lock for every chunk (kmp_dispatch.cpp, type_size > 4).
#pragma omp for schedule(runtime) nowait
      for (int ci = 0; ci < chunks32; ++ci) {
        const long long c = ci;
        const Clock::time_point claim = Clock::now();
        for (long long id = c * grain; id < std::min((c + 1) * grain, n); ++id) {
          if (id == o.fault_item && o.fault == Options::Fault::drop) continue;
          run_item(f, id, t);
          if (id == o.fault_item && o.fault == Options::Fault::dup) run_item(f, id, t);
        }
        workers[t].busy_ns += ns_since(claim);
      }
      workers[t].active_ns = ns_since(span);
      workers[t].cpu_ns = frontsteal::thread_cpu_ns() - cpu;
    }
    const std::int64_t wall = ns_since(start);
    if (static_ranges) {
      for (long long c = 0; c < chunks; ++c) {
        const int t = runner[c * grain];
        if (t >= 0 && t != owner_of(c, chunks, P)) {
          ++workers[t].chunks_stolen;
          workers[t].items_stolen += std::min((c + 1) * grain, n) - c * grain;
        }
      }
    }
    return wall;
  };

  run_frame(0);  // warm-up, untimed, as the main job does for every in-process scheduler
  for (auto& r : runs) r.store(0, std::memory_order_relaxed);
  std::cout << "ready items=" << n << " workers=" << P << " chunk=" << grain << " chunks=" << chunks
            << " schedule=" << o.schedule << " probe=confirmed:" << attempts
            << std::endl;

  std::string line;
  while (std::getline(std::cin, line)) {
    if (line == "quit") return 0;
    if (line != "path") {
      std::cout << "error unknown command '" << line << "'" << std::endl;
      return 2;
    }
    std::string out;
    for (int f = 0; f < o.frames; ++f) {
      std::fill(runner.begin(), runner.end(), -1);
      const std::int64_t wall = run_frame(f);
      std::uint64_t tri = 0, bad = 0;
      for (long long i = 0; i < n; ++i) tri += triangles[i], bad += inconsistent[i];
      out = "frame " + std::to_string(f) + ' ' + std::to_string(wall) + ' ' + std::to_string(tri) + ' ' +
            std::to_string(bad) + ' ' + std::to_string(P);
      for (const Worker& w : workers) {
        for (std::int64_t v : {w.items, w.busy_ns, w.active_ns, w.cpu_ns, w.chunks_stolen, w.items_stolen}) {
          out += ' ' + std::to_string(v);
        }
      }
      out += ' ';
      // Run-length encoding of the per-item execution counts (and reset them for the next frame).
      for (long long i = 0; i < n;) {
        const std::uint32_t v = runs[i].load(std::memory_order_relaxed);
        long long j = i;
        while (j < n && runs[j].load(std::memory_order_relaxed) == v) runs[j++].store(0, std::memory_order_relaxed);
        out += (i ? "," : "") + std::to_string(v) + '*' + std::to_string(j - i);
        i = j;
      }
      if (n == 0) out += "-";
      std::cout << out << '\n';
    }
    // libomp's idle threads spin for KMP_BLOCKTIME (200 ms by default, left as users get it: it is part of
    // libomp's frame-to-frame wake-up) before they sleep. Wait that out here, so their spinning falls in
    // this child's idle time and not on the next scheduler the main job measures (the main job's 5 ms
    // settling pause covers libgomp's much shorter spin, not this).
    std::this_thread::sleep_for(std::chrono::milliseconds(kmp_get_blocktime() + 20));
    std::cout << "end" << std::endl;
  }
  return 0;
}
