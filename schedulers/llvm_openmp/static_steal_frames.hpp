// static_steal_frames.hpp — the child's workload: the scene, cameras and settings prepared exactly as the main
// job prepares them, and one frame at a time under a schedule(runtime) loop (static_steal, set through
// OMP_SCHEDULE by the child's main), reported as one protocol line.
//
// Roles: the OpenMP team runs the items; each thread writes only its own Worker slot and the items it ran;
// the main thread reads everything after the parallel region (its barrier orders the writes). "Steals" are
// chunks run by a thread other than their static owner (static_steal_probe.hpp's range formula); with fewer
// chunks than threads libomp falls back to another schedule and steals are 0.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "measure/thread_pinning.hpp"
#include "schedulers/llvm_openmp/child_options.hpp"
#include "tessellate/frame_workload.hpp"
#include "tessellate/path_scene.hpp"

namespace frontsteal::llvm_openmp {

class StaticStealFrames {
 public:
  // Loads and prepares the scene; throws std::runtime_error ("cannot load scene ...") when it cannot.
  explicit StaticStealFrames(const Options& o);
  StaticStealFrames(const StaticStealFrames&) = delete;  // frames_ refers to scene_
  StaticStealFrames& operator=(const StaticStealFrames&) = delete;

  long long items() const noexcept { return n_; }
  long long chunks() const noexcept { return chunks_; }

  // Every frame of the path once, untimed: the buffers grown to their largest frame and their pages touched, as
  // the main job's serial warm-up pass did for the scene the in-process schedulers write (a child warmed on frame
  // 0 alone grew its buffers inside the measured zoom frames: +15-35 % at P = 1); the counts are reset.
  void warm_up();
  // Runs frame f and returns its protocol line (without the newline):
  //   frame <f> <wall_ns> <triangles> <inconsistent> <P> {<items> <claims> <busy_ns> <active_ns> <cpu_ns>
  //   <chunks_stolen> <items_stolen> <wake_ns> <termination_ns>} x P <runs>
  // with <runs> the per-item execution counts, run-length encoded ("count*length,..."), then reset. A thread's
  // busy time is its run of claims (first claim → the loop's end, one clock read pair per frame), as the parent's
  // fine-grained schedulers time theirs (schedulers/worker_team.hpp, WorkerSlot::begin_run); wake and
  // termination are its first claim's start and that end against the frame's start and end.
  std::string frame_line(int f);
  // With --reuse: the kept tessellations as after frame first − 1 (nothing kept for first = 0), so a segment
  // starting at `first` costs what it costs in frontsteal's in-process arms. Untimed; no-op without reuse.
  void prime(int first) { frames_->prime(first); }

 private:
  struct alignas(64) Worker {
    std::int64_t items = 0, claims = 0, busy_ns = 0, active_ns = 0, cpu_ns = 0, chunks_stolen = 0, items_stolen = 0,
                 wake_ns = 0, termination_ns = 0;
    std::vector<std::int32_t> ran;  // the ids this thread ran this frame, in order (its own memory: plain stores)
  };
  void run_item(int f, long long id, int t);
  std::int64_t run_frame(int f);  // returns the wall time (ns)
  std::string encoded_runs();     // <runs>, and the counts reset for the next frame

  Options o_;
  ts::PathScene scene_;  // the parent's views: the same tessellate/path_scene.cpp, from the same options
  std::optional<ts::FrameWorkload> frames_;  // over scene_, once it is loaded: the parent's items and totals
  long long n_ = 0, grain_ = 1, chunks_ = 0;
  std::vector<std::uint32_t> runs_;   // per item: runs this frame, counted from the threads' logs after the region
  std::vector<std::int32_t> runner_;  // the thread that last ran item i
  std::vector<Worker> workers_;
  const ThreadPinning pinning_;
};

}  // namespace frontsteal::llvm_openmp
