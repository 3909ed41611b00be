// llvm_openmp_child.hpp — openmp-static-steal: the main job's side of frontsteal-llvm-openmp, the executable
// that runs the tessellation workload under LLVM libomp's static_steal (schedulers/llvm_openmp/).
//
// Why a child process: the main job links libgomp (openmp-dynamic) and two OpenMP runtimes must not share a
// process. The child is persistent: started once per P, it prepares the same scene and camera path, proves
// that static_steal is in effect (its probe), runs one untimed warm-up frame and says "ready"; then each
// run_path() asks it for one whole path ("path\n") and reads one line per frame (wall time, per-worker busy,
// active and CPU time, steals, triangle count, per-item execution counts). So its repeats interleave with the
// in-process schedulers' repeats and get the same paired ratios and verdicts.
//
// The AUDIT is the parent's: exactly once per item per frame from the reported execution counts
// (audit_runs), triangles against the parent's serial loop (the caller compares). A planted fault in the
// child (--fault drop:K / dup:K) must be caught here — tests/schedulers/llvm_openmp_child_test.cpp.
//
// REAPING: the child is killed when its parent dies (PR_SET_PDEATHSIG, set between fork and exec) and exits
// on end of input; the destructor asks it to quit, waits up to 5 s, then SIGKILLs and reaps it. A child that
// stops answering makes run_path throw after `reply_timeout_s` (the destructor then kills it).
// The channel is a Unix socket pair (the child's stdin and stdout), written with MSG_NOSIGNAL: a dead child
// makes a write fail with EPIPE instead of killing the parent with SIGPIPE.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/frame_stats.hpp"
#include "core/id_range.hpp"

namespace frontsteal::sched {

inline constexpr std::string_view kLlvmOpenMpName = "openmp-static-steal";
inline constexpr std::string_view kLlvmOpenMpSummary =
    "LLVM libomp static_steal (clang++-14), in a child process, chunk N/(100P)";
// The same child with chunk 1, libomp's default: at P = 2 here each claim then cost ~0.2 us more than at P = 1
// (a cache line moving between the threads per claim), a fifth of the frame; kept to measure that against.
inline constexpr std::string_view kLlvmOpenMpChunk1Name = "openmp-static-steal:chunk1";
inline constexpr std::string_view kLlvmOpenMpChunk1Summary =
    "variant of openmp-static-steal: chunk 1 (libomp's default)";

// The child executable this build made (FRONTSTEAL_LLVM_OPENMP overrides it), and why it is not available
// ("" when it is: built, and the file exists).
std::string llvm_openmp_child_path();
std::string llvm_openmp_unavailable_reason();

// What the child must reproduce of the main job's workload.
struct ChildWorkload {
  std::string scene = "plant:15906";
  int frames = 24;
  std::string path = "orbit-then-zoom";  // tessellate/camera_path.hpp name()
  double tolerance = 1.0;
  int width = 1280, height = 720;
  ItemId grain = 0;          // 0: the child's default, 1 (as openmp-dynamic)
  std::string plant_defect;  // "" or frontsteal's --plant-defect value
  bool pin = false;
  std::vector<std::string> extra_args;  // passed as they are: --fault, --schedule (negative controls)
};

// One frame as the child reported it.
struct ChildFrame {
  FrameStats stats;                // wall, and per worker: items, busy, active, cpu, steals
  std::uint64_t triangles = 0;     // the frame's triangle count
  std::uint64_t inconsistent = 0;  // surfaces whose tessellation audit failed
  ExecutionAudit audit;            // exactly once, from the reported per-item execution counts
};

// The parent's exactly-once audit of per-item execution counts (ExecutionCounter's rules).
ExecutionAudit audit_runs(const std::vector<std::uint32_t>& runs);
// Decodes the child's "count*length,..." encoding; false if malformed or not `items` long.
bool decode_runs(std::string_view text, ItemId items, std::vector<std::uint32_t>& out);

class LlvmOpenMpChild {
 public:
  // Starts the child with P = workers and waits for "ready" (preparing a large scene takes seconds).
  // Throws std::runtime_error with the reason when it cannot start, says "error ...", or reports another item
  // count than `items`.
  LlvmOpenMpChild(WorkerId workers, ItemId items, const ChildWorkload& workload, double reply_timeout_s = 600,
                  std::string executable = llvm_openmp_child_path());
  LlvmOpenMpChild(const LlvmOpenMpChild&) = delete;
  LlvmOpenMpChild& operator=(const LlvmOpenMpChild&) = delete;
  ~LlvmOpenMpChild();

  // Runs the whole camera path once in the child; one entry per frame. Throws std::runtime_error when the
  // child fails, stops answering, or breaks the protocol.
  std::vector<ChildFrame> run_path();
  // Runs frames [first, last) of the path in the child (one round's segment); one entry per frame.
  std::vector<ChildFrame> run_frames(int first, int last);

  const std::string& ready_line() const noexcept { return ready_; }
  pid_t pid() const noexcept { return pid_; }
  WorkerId worker_count() const noexcept { return workers_; }
  // The child's CPU time so far (utime + stime from /proc/<pid>/stat, clock ticks): the noise monitor counts
  // it as ours, not as another process's.
  std::uint64_t cpu_ticks() const;

 private:
  std::string read_line();
  void send(std::string_view text);
  void reap();

  WorkerId workers_;
  ItemId items_;
  int frames_;
  double timeout_s_;
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string buffer_;
  std::string ready_;
  std::uint64_t frame_counter_ = 0;
};

}  // namespace frontsteal::sched
