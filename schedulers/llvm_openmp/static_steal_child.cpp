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
// KMP_SETTINGS prints but not the loops (measured with the probe, static_steal_probe.hpp: no steal).
// static_steal (kmp_dispatch.cpp): thread t owns the contiguous chunk range starting at t * (K / P) +
// min(t, K % P) of the K chunks, takes from its front, and a thief takes from a victim's back. The child
// PROVES that it is in effect before it says ready: static_steal_probe.hpp.
//
// PROTOCOL (one line each way; the parent writes, the child answers):
//   start-up          the child prepares the scene and cameras, proves the schedule, runs frame 0 once
//                     untimed, and prints  "ready items=N workers=P chunk=C chunks=K schedule=static-steal
//                     probe=confirmed:<attempts>"  or  "error <reason>"  (exit 1).
//   "path"            runs every frame of the path, one line per frame:
//                       frame <f> <wall_ns> <triangles> <inconsistent> <P> {<items> <claims> <busy_ns>
//                       <active_ns> <cpu_ns> <chunks_stolen> <items_stolen> <wake_ns> <termination_ns>} x P
//                       <runs>
//                     with <runs> the per-item execution counts of the frame, run-length encoded as
//                     "count*length,count*length,..." (all ones: "1*N"); then, once libomp's threads
//                     are asleep (settle(): a soft pause, checked), "end".
//   "frames A B"      runs frames A .. B-1 only (a round of the main job covers a segment of the path), the same
//                     lines and the same "end".
//   "quit" or EOF     exit 0. The child also dies with its parent (PR_SET_PDEATHSIG, set by the parent).
// The parent audits: exactly once from <runs>, triangles against its own serial loop.
// --fault drop:K | dup:K  (negative controls) skip item K in every frame, or run it twice: the parent must
// catch either.
//
// The pieces: the options (child_options.hpp, CLI11), the probe (static_steal_probe.hpp), the workload and its
// frames (static_steal_frames.hpp); this file is the protocol loop.
#include <omp.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>

#include "schedulers/llvm_openmp/child_options.hpp"
#include "schedulers/llvm_openmp/static_steal_frames.hpp"
#include "schedulers/llvm_openmp/static_steal_probe.hpp"

namespace lo = frontsteal::llvm_openmp;

namespace {

// The schedule of every schedule(runtime) loop: libomp reads it from the environment when it is loaded, so
// set it and start again (once; see the header). Returns only when OMP_SCHEDULE is the one wanted; otherwise
// it re-executes this program or, failing that, says "error" and exits 1.
void ensure_schedule(const std::string& schedule, char** argv) {
  const char* want = schedule == "static-steal"        ? "static_steal,1"
                     : schedule == "monotonic-dynamic" ? "monotonic:dynamic,1"
                                                       : "static";
  if (const char* have = std::getenv("OMP_SCHEDULE"); have && std::string_view(have) == want) return;
  if (std::getenv("FRONTSTEAL_LLVM_OPENMP_REEXEC")) {
    std::cout << "error OMP_SCHEDULE=" << want << " did not survive re-execution" << std::endl;
    std::exit(1);
  }
  ::setenv("OMP_SCHEDULE", want, 1);
  ::setenv("FRONTSTEAL_LLVM_OPENMP_REEXEC", "1", 1);
  ::execv("/proc/self/exe", argv);
  std::cout << "error cannot re-execute /proc/self/exe: " << std::strerror(errno) << std::endl;
  std::exit(1);
}

// CPU time of the whole process, ns.
std::int64_t process_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

// libomp's idle threads spin for KMP_BLOCKTIME (200 ms by default, left as users get it: it is part of libomp's
// frame-to-frame wake-up inside a run of frames) before they sleep. Their spinning must not fall on the next
// scheduler the main job measures, so after a run of frames the threads are put to sleep at once with a soft
// pause (OpenMP 5.0 omp_pause_resource_all; the next parallel region resumes them, as a frame after the block
// time would). Checked, not assumed: when the process still burns more than half a core over 10 ms with this
// thread asleep, the threads are spinning, and the block time is waited out instead.
void settle() {
  omp_pause_resource_all(omp_pause_soft);
  const std::int64_t cpu0 = process_cpu_ns();
  std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (process_cpu_ns() - cpu0 > 5'000'000)
    std::this_thread::sleep_for(std::chrono::milliseconds(kmp_get_blocktime() + 20));
}

}  // namespace

int main(int argc, char** argv) {
  const lo::Options o = lo::parse_options(argc, argv);
  ensure_schedule(o.schedule, argv);
  std::unique_ptr<lo::StaticStealFrames> frames;  // the workload, exactly as the main job prepares it
  try {
    frames = std::make_unique<lo::StaticStealFrames>(o);
  } catch (const std::exception& e) {
    std::cout << "error " << e.what() << std::endl;
    return 1;
  }
  const int attempts = lo::probe_static_steal(o.workers);
  if (attempts == 0) {
    std::cout << "error static_steal not in effect: the probe did not see every thread start at its static range "
                 "and then steal (schedule requested: "
              << o.schedule << ")" << std::endl;
    return 1;
  }
  if (frames->chunks() > std::numeric_limits<int>::max()) {
    std::cout << "error " << frames->chunks() << " chunks: more than a 32-bit loop counts (use --grain)" << std::endl;
    return 1;
  }
  frames->warm_up();
  std::cout << "ready items=" << frames->items() << " workers=" << o.workers << " chunk=" << o.grain
            << " chunks=" << frames->chunks() << " schedule=" << o.schedule << " probe=confirmed:" << attempts
            << std::endl;

  std::string line;
  while (std::getline(std::cin, line)) {
    if (line == "quit") return 0;
    int first = 0, last = o.frames;
    if (line.rfind("frames ", 0) == 0) {
      std::istringstream range(line.substr(7));
      if (!(range >> first >> last) || first < 0 || last > o.frames || first >= last) {
        std::cout << "error bad frame range '" << line << "' (the path has " << o.frames << " frames)" << std::endl;
        return 2;
      }
    } else if (line != "path") {
      std::cout << "error unknown command '" << line << "'" << std::endl;
      return 2;
    }
    frames->prime(first);  // with reuse: the state frontsteal's other arms start this segment from
    for (int f = first; f < last; ++f) std::cout << frames->frame_line(f) << '\n';
    settle();
    std::cout << "end" << std::endl;
  }
  return 0;
}
