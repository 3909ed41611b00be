// limit_arm.hpp — the machine's own throughput limit at P: P independent copies of the serial loop at once.
//
// The limit arm runs P whole frames at the same time, one per worker thread of a team (pinned as the
// schedulers' workers are, by the caller's pin function), each copy tessellating every surface of the frame
// into buffers of its own (tessellate/frame_workload.hpp, Buffers::kOwn). Copy w's loop takes t_w (the harness's
// clock, around the loop on its thread); together the copies deliver sum_w 1 / t_w frames per unit of time, so
// the machine's throughput limit at P is one frame per
//   L = 1 / sum_w (1 / t_w)        (= t / P when every copy takes t)
// with P busy cores and no scheduling at all: it pays every hardware effect of P busy cores (shared caches,
// memory bandwidth, a lower clock) and nothing else. A scheduler's limit-efficiency is L / T_scheduler, paired
// per round. The arm's wall time W (release → the last copy done) is kept too: W / P is the literal "P serial
// loops, frame time over P", which also charges the limit with the team's wake-up and join and with its slowest
// copy (on these VMs the vCPUs differ in speed by a few per cent, and a scheduler that balances load uses the
// faster one more): a bound a scheduler can beat, reported beside L, never used as the limit.
//
// Why copies and not one frame split P ways: any split of one frame is a schedule; P copies have none to lose.
//
// Where the copies' buffers lie matters as much as a scheduler would: in the main job, buffers allocated after
// the schedulers' set-up made the same surfaces 5-10 % slower than the scene's own buffers (the serial loop's and
// every scheduler's), measured with a copy on the scene's buffers as the control. So the copies are a pool made
// before anything else and grown in the serial warm-up pass, surface by surface beside the scene's buffers
// (LimitCopies::grow), and every limit arm (one per P) runs the first P copies of the one pool.
//
// Roles: the caller (the main job's thread) runs frames; copy w belongs to team worker w during a frame and to
// the caller between frames (the team's release and arrival order them: schedulers/worker_team.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/id_range.hpp"
#include "measure/item_sampler.hpp"
#include "schedulers/worker_team.hpp"
#include "tessellate/frame_workload.hpp"

namespace frontsteal::main_job {

namespace ts = frontsteal::tess;

// The copies of the serial loop's workload every limit arm runs: `copies` frame workloads over one scene, each
// with its own buffers and scratch.
class LimitCopies {
 public:
  LimitCopies(ts::PathScene& scene, WorkerId copies, bool reuse);
  // Surface `id` of frame `f` on every copy, one after another on the calling thread (the warm-up pass).
  void grow(int f, ItemId id);
  // --reuse: every copy made to start frame `first` from the same kept state (untimed; serial).
  void prime(int first, WorkerId copies);
  ts::FrameWorkload& copy(WorkerId w) { return *copies_[w]; }
  WorkerId size() const noexcept { return static_cast<WorkerId>(copies_.size()); }

 private:
  std::vector<std::unique_ptr<ts::FrameWorkload>> copies_;
};

// One frame of the limit arm, as its copies left it.
struct LimitFrame {
  sched::FrameWindow window;
  // The machine's throughput limit for this frame, L = 1 / sum_w (1 / t_w), in ns.
  double throughput_ns() const {
    double rate = 0;
    for (const std::int64_t t : copy_ns) rate += t > 0 ? 1.0 / static_cast<double>(t) : 0.0;
    return rate > 0 ? 1.0 / rate : 0.0;
  }
  std::vector<std::int64_t> copy_ns;        // per copy: its own loop's time
  std::vector<std::uint64_t> triangles;     // per copy: the frame's triangle count
  std::vector<std::uint64_t> inconsistent;  // per copy: surfaces whose tessellation audit failed
};

class LimitArm {
 public:
  // The first P copies of `pool` (which must outlive the arm, and hold at least P). `pin(w)` runs on team
  // worker w before its copy's loop; `sampler` times the sampled surfaces (its lanes 0 .. P-1).
  LimitArm(LimitCopies& pool, WorkerId p, std::function<void(WorkerId)> pin, measure::ItemSampler& sampler);

  void prime(int first) { pool_.prime(first, p_); }
  // Frame f on every copy at once.
  const LimitFrame& run_frame(int f);
  WorkerId copies() const noexcept { return p_; }

 private:
  void copy_loop(WorkerId w);

  LimitCopies& pool_;
  WorkerId p_;
  std::function<void(WorkerId)> pin_;
  measure::ItemSampler& sampler_;
  int frame_ = 0;
  LimitFrame last_;
  sched::WorkerTeam team_;  // last: its threads start once everything they touch exists
};

}  // namespace frontsteal::main_job
