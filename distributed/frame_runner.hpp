// frame_runner.hpp — one rank's part of a frame under each scheduler of frontsteal-mpi:
//   rma       load stealing: core/'s protocol with each rank's slot in an MPI-3 window (window_protocol.hpp):
//             the owner claims locally, thieves steal with one-sided operations; the busy rank never answers
//             anyone (but may call into MPI for the transport's sake: owner_progress.hpp).
//   request   request-based stealing (§7: "request based load stealing, but overhead on the busy processors
//             must increase"): an idle rank sends a steal request; the busy owner polls (MPI_Iprobe) between
//             items and replies with the second half of its remaining list.
//   central   a central counter in rank 0's window (MPI_Fetch_and_op), grain N/(100P) as §4.1.
//   static    static round robin over ranks (§3), no communication.
//   static-space  static contiguous blocks of ids (regions of space, as a cluster renderer assigns them).
//   hier      ranks x threads (hierarchical_rank.hpp): core's protocol among the rank's --threads workers over
//             the rank's list, and over the window between ranks once every worker of a rank is dry.
//   rma-seeded  rma whose lists at each frame start are contiguous blocks of equal measured cost of the last
//             frame (cost_seeded_lists.hpp) instead of what each rank processed.
// TERMINATION inside a frame: the active count of core/active_workers.hpp (I-T) in rank 0's window
// (WindowProtocol's): not a master, rank 0 runs no code for it (passive target). The request scheduler ends its
// frame with MPI_Ibarrier while still answering requests (empty), so no request is left unanswered.
// FAULTS: --stall, --slow and --die act after the rank's first item of the named frame (execute()).
#pragma once

#include <mpi.h>

#include <chrono>
#include <memory>
#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "core/policies.hpp"
#include "distributed/mpi_options.hpp"
#include "distributed/mpi_workload.hpp"
#include "distributed/os_slowdown.hpp"
#include "distributed/owner_progress.hpp"
#include "distributed/rank_stats.hpp"
#include "distributed/rma_window.hpp"
#include "distributed/window_protocol.hpp"

namespace frontsteal::mpi {

// The schedulers that run core's protocol over the window (rma, rma with cost-seeded lists, and hier at the rank
// level: hierarchical_rank.hpp).
inline bool runs_window_protocol(const std::string& scheduler) {
  return scheduler == "rma" || scheduler == "rma-seeded" || scheduler == "hier" || scheduler == "hier-seeded";
}

inline constexpr int kTagRequest = 181;
inline constexpr int kTagReply = 182;

// One frame on this rank: its number, the per-item execution counts (the audit) and its triangles.
struct Frame {
  int f;
  std::vector<std::uint32_t>* counts;
  std::uint64_t triangles = 0;
};

class FrameRunner {
 public:
  using Clock = std::chrono::steady_clock;
  FrameRunner(const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win, double owner_progress_us);

  void begin_frame(const std::string& scheduler);
  void rma_frame(Frame& fr, RangeList& log);
  void request_frame(Frame& fr, RangeList list, RangeList& log);
  void central_frame(Frame& fr);
  void static_frame(Frame& fr);
  void static_space_frame(Frame& fr);

  // Adds what another runner of this rank measured (hier's threads: the additive fields) and its steal latencies.
  void absorb(const RankStats& extra, const std::vector<double>& steal_latencies_us);
  // The rank's statistics, with the medians and their 95 % bootstrap intervals filled in.
  RankStats& finish_stats();
  WindowProtocol& protocol() { return *protocol_; }
  // The other ranks in this rank's random victim order (§4.2.1).
  const std::vector<int>& victims() const { return victims_; }
  // rma-seeded: seconds each item of the current frame took on this rank (0 for items other ranks ran).
  std::vector<float>& item_costs() { return item_costs_; }

  // The fault hooks, after this rank's first item of `frame` (--die, --stall, --slow): every runner of the rank
  // calls them once per frame, hier's main thread included.
  void first_item_faults(int frame);
  // --slow under a window scheduler: says whether thieves lowered this rank's End since the slowdown began; the
  // rank calls it when its own list has run out in the slowed frame.
  void report_slowdown();

 private:
  void execute(Frame& fr, ItemId id);
  void stall(int frame);
  void start_slowdown(int frame);
  void drain_rma(Frame& fr, RangeList& log);
  void drain_request(Frame& fr, RangeList list, RangeList& log);
  void serve_requests(RangeList* list, std::size_t* index = nullptr);
  void record_owner_op(Clock::duration d);
  void record_steal(Clock::duration d);

  const Options& o_;
  Workload& wl_;
  int rank_, ranks_;
  RmaWindow& win_;
  std::unique_ptr<WindowProtocol> protocol_;
  OwnerProgress progress_;
  // The request owner's poll: every item when the rma owner needs no progress calls (Open MPI's osc/sm),
  // else at the same interval (--owner-progress): over TCP a poll costs ~4-5 us, and polling after every
  // 1 us item was measured to leave requests unanswered until the owner ran dry (docs/mpi.md, "Two hosts").
  PollGate request_poll_;
  std::vector<int> victims_;
  RankStats stats_;
  std::vector<float> owner_samples_;
  std::vector<double> steal_latencies_us_;
  bool first_item_done_ = false;
  OsSlowdown slowdown_;
  std::vector<float> item_costs_;      // rma-seeded only, else empty
  std::int64_t slow_end_before_ = -1;  // this rank's End when --slow began (rma), until reported
  const std::string* scheduler_ = nullptr;
};

}  // namespace frontsteal::mpi
