// rank_stats.hpp — what one rank measured under one scheduler, gathered to rank 0 as a flat array of doubles
// (MPI_Gather of kRankStatFields MPI_DOUBLEs), and what rank 0 keeps per scheduler.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace frontsteal::mpi {

struct RankStats {
  double busy_s = 0;  // time inside item functions
  double items = 0;
  double steals = 0;           // successful steals (non-empty shares received)
  double steal_attempts = 0;   // try_steal calls / requests sent
  double steal_latency_s = 0;  // summed over successful steals
  double steal_latency_max_s = 0;
  double bytes = 0;             // RMA payload bytes issued + message bytes sent by this rank
  double owner_overhead_s = 0;  // owner-path protocol time (claims, polls, progress calls), measured around them
  double owner_ops = 0;         // claims (rma) / polls (request) / counter grabs (central)
  double requests_served = 0;
  double owner_overhead_median_ns = 0;  // median of the recorded owner-path samples (robust to preemption)
  double t4_wait_s = 0;                 // rma thief: time waiting at T4 for a victim's claim in flight
  double t4_spins = 0;
  double idle_s = 0;          // time in the idle (stealing / requesting) loop, steals' work excluded
  double progress_calls = 0;  // rma owner: MPI_Iprobe calls made for target progress (--owner-progress)
  // Medians with 95 % percentile-bootstrap intervals (measure/paired_comparison.hpp), computed on the rank.
  double steal_latency_median_us = 0, steal_latency_ci_low_us = 0, steal_latency_ci_high_us = 0;
  double owner_overhead_ci_low_ns = 0, owner_overhead_ci_high_ns = 0;
  double local_steals = 0;      // hier: steals between the rank's own worker threads
  double steal_operations = 0;  // rma, hier: one-sided operations spent by the successful steals (rma_backend.hpp)
};
inline constexpr int kRankStatFields = sizeof(RankStats) / sizeof(double);

// The noise monitor's verdict over one scheduler's frames, across every node (noise_window.hpp).
struct NoiseVerdict {
  bool busy = false;
  std::string reason;          // empty when quiet
  double other_share_max = 0;  // the largest share of a node's CPU taken by processes that are not ranks
  double steal_share_max = 0;
  double load1 = 0;  // rank 0's node, at the end
};

struct SchedulerResult {
  std::string name;
  std::vector<double> frame_s;   // rank 0's wall time per frame
  std::vector<RankStats> ranks;  // gathered on rank 0
  std::uint64_t audited_frames = 0;
  NoiseVerdict noise;
};

}  // namespace frontsteal::mpi
