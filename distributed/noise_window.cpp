// noise_window.cpp — the noise monitor across ranks (noise_window.hpp).
#include "distributed/noise_window.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace frontsteal::mpi {

void NoiseWindow::start() {
  MPI_Barrier(MPI_COMM_WORLD);
  before_ = noise::sample_now();
}

namespace {

// One rank's window, as rank 0 needs it: its node (a hash of MPI_Get_processor_name), its own ticks and the
// machine-wide counters it read (every rank of a node reads the same /proc, a few ticks apart).
struct RankWindow {
  unsigned long long node, self, total, busy, steal, known, children;
  double wall_s;
  int ok;
};

unsigned long long node_key() {
  char name[MPI_MAX_PROCESSOR_NAME];
  int length = 0;
  MPI_Get_processor_name(name, &length);
  unsigned long long h = 1469598103934665603ull;  // FNV-1a
  for (int i = 0; i < length; ++i) h = (h ^ static_cast<unsigned char>(name[i])) * 1099511628211ull;
  return h;
}

}  // namespace

NoiseVerdict NoiseWindow::finish() {
  MPI_Barrier(MPI_COMM_WORLD);
  const noise::ProcSample after = noise::sample_now();
  const noise::Usage u = noise::usage_between(before_, after);
  // Gathered to rank 0 over MPI_COMM_WORLD as plain numbers, not reduced over a node communicator made per
  // window: Open MPI 4.1's ob1 crashed (null communicator in recv_frag_callback_match) when a fresh
  // MPI_COMM_TYPE_SHARED communicator spanned ranks on two hosts over TCP.
  const RankWindow mine{node_key(),    u.self_ticks,     u.total_ticks, u.busy_ticks, u.steal_ticks,
                        u.known_ticks, u.children_ticks, u.wall_s,      u.ok ? 1 : 0};
  int ranks = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::vector<RankWindow> all(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
  // Per node (its first rank's counters; the sum of its ranks' own and their children's ticks): busy flag,
  // other share, steal share; the worst over nodes is the verdict.
  double worst[3] = {0, 0, 0};
  std::string reason;
  for (std::size_t first = 0; first < all.size(); ++first) {
    bool seen = false;
    for (std::size_t j = 0; j < first; ++j) seen = seen || all[j].node == all[first].node;
    if (seen) continue;
    noise::Usage node;
    node.total_ticks = all[first].total;
    node.busy_ticks = all[first].busy;
    node.steal_ticks = all[first].steal;
    node.known_ticks = all[first].known;
    node.wall_s = all[first].wall_s;
    node.windows = 1;
    for (const RankWindow& r : all) {
      if (r.node != all[first].node) continue;
      node.self_ticks += r.self;
      node.children_ticks += r.children;  // each rank's own child processes are ours too
      node.ok = node.ok && r.ok == 1;
    }
    const noise::Assessment a = noise::assess(node, thresholds_);
    if (a.busy && reason.empty()) reason = a.reason;
    worst[0] = std::max(worst[0], a.busy ? 1.0 : 0.0);
    worst[1] = std::max(worst[1], node.other_share());
    worst[2] = std::max(worst[2], node.steal_share());
  }
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
