// noise_window.cpp — the noise monitor across ranks (noise_window.hpp).
#include "distributed/noise_window.hpp"

#include <cstdio>
#include <string>

namespace frontsteal::mpi {

void NoiseWindow::start() {
  MPI_Barrier(MPI_COMM_WORLD);
  before_ = noise::sample_now();
}

NoiseVerdict NoiseWindow::finish() {
  MPI_Barrier(MPI_COMM_WORLD);
  const noise::ProcSample after = noise::sample_now();
  noise::Usage u = noise::usage_between(before_, after);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int node_rank = 0;
  MPI_Comm_rank(node, &node_rank);
  unsigned long long self = u.self_ticks, node_self = 0;
  int ok = u.ok ? 1 : 0, node_ok = 0;
  MPI_Reduce(&self, &node_self, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, node);
  MPI_Reduce(&ok, &node_ok, 1, MPI_INT, MPI_MIN, 0, node);
  MPI_Comm_free(&node);
  // Per node (its first rank): busy flag, other share, steal share; the worst over nodes goes to rank 0.
  double mine[3] = {0, 0, 0};
  std::string reason;
  if (node_rank == 0) {
    u.self_ticks = node_self;
    u.ok = node_ok == 1;
    const noise::Assessment a = noise::assess(u, thresholds_);
    mine[0] = a.busy ? 1 : 0;
    mine[1] = u.other_share();
    mine[2] = u.steal_share();
    reason = a.reason;
  }
  double worst[3] = {0, 0, 0};
  MPI_Reduce(mine, worst, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  NoiseVerdict v;
  v.busy = worst[0] > 0;
  v.other_share_max = worst[1];
  v.steal_share_max = worst[2];
  v.load1 = after.load1;
  if (v.busy) {
    char text[160];
    std::snprintf(text, sizeof text, "worst node: other processes %.1f %%, steal %.1f %% of the CPU", 100 * worst[1],
                  100 * worst[2]);
    v.reason = reason.empty() ? text : reason + " (" + text + ")";
  }
  return v;
}

}  // namespace frontsteal::mpi
