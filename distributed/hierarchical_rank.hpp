// hierarchical_rank.hpp — ranks x threads: one rank's worker threads running core's stealing protocol among
// themselves (std atomics), over the rank's list in the MPI window (core's protocol again, window_protocol.hpp).
// The `hier` scheduler of frontsteal-mpi.
//
// ROLES (one HierarchicalRank per rank; T = --threads)
//   worker t     a thread (t = 0 is the rank's main thread, the only one that calls MPI: MPI_THREAD_FUNNELED).
//                Owner of local slot t (core Owner<StdBackend, Fenced>), thief of the other local slots (core
//                Thief<StdBackend, Fenced>).
//   the rank     owner of the rank's window slot (core Owner over RmaBackend): its claims are made by any worker,
//                one at a time under `rank_mutex_` (the mutex orders them: one logical owner, as the protocol
//                requires); its installs and every remote operation by worker 0 only.
//
// THE LOOP of every worker, until the frame is over:
//   1. claim and run items from its own local list (wait-free);
//   2. list empty: refill it with a chunk of the rank list — items claimed under rank_mutex_, one owner
//      handshake per run of consecutive ids (--batch-claims on; one per item off), until they are worth
//      ~--chunk-us by the last frame's item times (an item without one as refill_budget.hpp says: priced by the
//      worker's last item, their number capped): the rank list stays stealable by other ranks except for the
//      chunks taken from it;
//   3. the rank list empty: steal half of a sibling's local list (node-local victims before remote ones);
//   4. nothing in the rank: worker 0, once every local worker is dry (the local active count is 0 under
//      rank_mutex_), leaves the global active count (A2 for the rank) and steals from other ranks (one-sided
//      operations; core takes half of the victim's unclaimed rank list), installing a share into the rank list
//      for every worker to refill from; the others back off (at most sibling_backoff_cap_us, idle_backoff.hpp)
//      and retry steps 2-3. A round tries at most 8 victims (continuing where the last round stopped). Then,
//      with --lifelines on (the default), the rank registers at its lifelines, reads the global count and waits
//      on its own window words for an invitation or the frame's end (lifelines.hpp), trying one more round of
//      random victims after 1 ms of waiting and then at doubling intervals up to 16 ms (a donor stopped by the
//      OS cannot invite, but its list can be stolen one-sidedly); with --lifelines off it backs off and
//      re-reads the global count before its next round.
// TERMINATION. Locally: a worker counts in `local_active_` (core ActiveWorkers over std atomics) while it holds
// work; it joins under rank_mutex_ before claiming a chunk, local thieves join on a victim's behalf (A1, inside
// core). Globally: the window's active count (one per rank, I-T); worker 0 ends the frame when it reads 0, or,
// with lifelines, when the notice reaches it (lifelines.hpp, L1-L2). When
// worker 0 finds every local worker dry and the rank list empty, no work can appear in this rank except through
// worker 0's own remote steal, so the frame's end is declared only when no rank holds work.
// EXACTLY ONCE: every item of the rank list is claimed once (core over the window, the rank's claims serialized),
// lands in one local list, and is claimed there once (core over std atomics); the audit checks it (scheduler_run).
// NEXT FRAME: the rank's next list is every item its workers ran this frame, stolen work included (§4.2.1 at the
// rank level); local lists start empty. Every item's time is recorded (item_costs): the next frame's refills are
// priced with it, and hier-seeded's caller cuts cost-balanced blocks from every rank's (cost_seeded_lists.hpp).
// WAKE-UPS: a worker other than 0 that found nothing backs off (idle_backoff.hpp) on a condition variable, and
// worker 0 wakes them when it installs a remote share and when the frame ends: with a few ranks holding the
// work, a rank's threads otherwise sleep through up to 256 us of a share or of the frame's end.
#pragma once

#include <atomic>
#include <barrier>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/id_range.hpp"
#include "core/std_backend.hpp"
#include "core/stealing_protocol.hpp"
#include "distributed/lifelines.hpp"
#include "distributed/mpi_options.hpp"
#include "distributed/mpi_workload.hpp"
#include "distributed/owner_progress.hpp"
#include "distributed/rank_stats.hpp"
#include "distributed/window_protocol.hpp"

namespace frontsteal::mpi {

// What the rank's fault hooks (frame_runner.hpp) are told, on worker 0: its first item of a frame, and the first
// time in a frame that the rank ran dry (its list exhausted, every worker idle).
struct HierFaultHooks {
  std::function<void(int frame)> first_item;
  std::function<void()> rank_dry;
};

class HierarchicalRank {
 public:
  // `remote_victims`: the other ranks, in this rank's random order. Starts T - 1 threads that wait for frames.
  // `owner_progress_us`: worker 0 calls into MPI between items at most this often (owner_progress.hpp), so that
  // other ranks' one-sided operations on this rank's window complete where the transport needs it (TCP).
  // `lifelines`: the rank's lifelines (--lifelines on), or null.
  HierarchicalRank(const Options& o, Workload& wl, int rank, WindowProtocol& window, std::vector<int> remote_victims,
                   double owner_progress_us, Lifelines* lifelines, HierFaultHooks faults = {});
  ~HierarchicalRank();
  HierarchicalRank(const HierarchicalRank&) = delete;
  HierarchicalRank& operator=(const HierarchicalRank&) = delete;

  // One frame, on the rank's main thread, between the frame's barriers, after the rank list was installed and the
  // active count re-armed. Adds to counts (atomically: the audit) and triangles; `log` receives the rank's items.
  void run_frame(int frame, std::vector<std::uint32_t>& counts, std::uint64_t& triangles, RangeList& log);
  // Adds this rank's totals (busy time, items, steals, attempts, latencies, local steals) to `s`.
  void add_stats(RankStats& s) const;
  // Remote steal latencies (us), for the medians.
  const std::vector<double>& steal_latencies_us() const { return steal_latencies_us_; }
  // Seconds per item id this rank ran in the last frame (0 for the others); until the next run_frame.
  std::vector<float>& item_costs() { return item_costs_; }
  // hier-seeded: the next frame's refills are priced with these (every rank's times, reduced) instead of this
  // rank's own.
  void use_costs(const std::vector<float>& costs);

 private:
  using LocalSlot = ActivitySlot<StdBackend, Fenced>;
  struct Worker;

  void worker_main(std::uint32_t t);
  void work(std::uint32_t t);
  bool refill(Worker& w);
  bool remote_step(std::uint32_t& failed_rounds);
  StealOutcome try_remote(int victim);               // worker 0: one steal attempt; on kStolen the share is installed
  bool end_frame(bool from_count);                   // worker 0: the frame is over; returns false
  bool lifeline_wait(std::uint32_t& failed_rounds);  // worker 0, registered: its own words, and rare probes
  void begin_waiting();
  void execute(Worker& w, ItemId id);
  void idle_wait(std::uint32_t failed_rounds);  // a worker other than 0 backs off until woken
  void wake_workers();                          // worker 0: a share arrived or the frame is over

  const Options& o_;
  Workload& wl_;
  int rank_;
  WindowProtocol& window_;
  std::vector<int> remote_victims_;
  OwnerProgress progress_;  // worker 0 only
  std::uint32_t threads_;

  ActiveWorkers<StdBackend, Fenced> local_active_;
  std::vector<std::unique_ptr<LocalSlot>> slots_;
  std::vector<std::unique_ptr<Worker>> workers_;
  std::mutex rank_mutex_;    // serializes the rank's claims and installs on its window slot
  bool rank_active_ = true;  // worker 0 only: this rank counts in the window's active count
  std::atomic<bool> frame_over_{false};
  std::mutex wake_mutex_;
  std::condition_variable wake_;
  std::uint64_t wake_generation_ = 0;  // under wake_mutex_
  std::vector<float> item_costs_;      // this frame's item times (s), written by the worker that ran the item
  std::vector<float> last_costs_;      // the last frame's: what refills are priced with
  bool shared_costs_given_ = false;    // use_costs() was called for the next frame
  std::size_t next_victim_ = 0;        // worker 0: where its next round of remote victims starts
  Lifelines* lifelines_ = nullptr;     // worker 0 only
  bool waiting_ = false;               // worker 0: registered at its lifelines, waiting
  std::chrono::steady_clock::time_point next_probe_{};  // worker 0, waiting: its next round of random victims
  std::chrono::steady_clock::duration probe_interval_{};
  HierFaultHooks faults_;
  std::atomic<bool> first_item_done_{false};  // any worker, this frame: the first item's faults ran
  bool dry_reported_ = false;                 // worker 0, this frame
  std::atomic<bool> stop_{false};
  std::barrier<> start_, end_;
  std::vector<std::thread> threads_started_;

  // The frame in progress (written by worker 0 before start_, read by every worker after it).
  int frame_ = 0;
  std::vector<std::uint32_t>* counts_ = nullptr;

  // Worker 0's remote statistics.
  double progress_calls_ = 0;
  double remote_steals_ = 0, remote_attempts_ = 0, steal_latency_s_ = 0, steal_latency_max_s_ = 0, idle_s_ = 0;
  std::chrono::steady_clock::time_point idle_start_{};  // worker 0: when the current remote step began
  std::vector<double> steal_latencies_us_;
};

}  // namespace frontsteal::mpi
