// rma_simulator.hpp — SIMULATED: a discrete-event model of frontsteal-mpi's four schedulers (rma stealing,
// request-based stealing, central counter, static round robin) at rank counts this machine cannot run
// (16, 64, 256), driven by latencies measured with frontsteal-mpi --calibrate. Every number it prints is a
// prediction of the model, labelled SIMULATED with the latencies used; none is a measurement.
//
// THE MODEL (one event per item boundary and per one-sided operation, processed in time order):
//   items       a synthetic cost shape of frontsteal-mpi (synthetic_cost.hpp, priced identically): skewed (light
//               `light_ns`, the moving heavy fifth `skew` x) or cascade (cost concentrated in space, mean
//               `light_ns`); lists carry over between frames (§4.2.1) as in frontsteal-mpi.
//   rma         the owner pays `claim` per item (+ `progress_call`, at most every `progress_every`, when the
//               transport needs target progress);
//               a thief runs the protocol's operations in order, as rma_backend.hpp issues them — L2 fetch-op
//               (the exchange; no L1 probe), one get for T1, T2, the entry count and the entries (the thief's
//               view, priced as a 4-byte get: --calibrate times the view too), A1 fetch-op on rank 0, T3 put,
//               T4 get, T5 get, L3 fetch-op: 7 operations, each a round trip of its calibrated latency (a busy
//               lock costs the exchange alone). The victim's End drops when T3
//               completes; items the victim claimed past mid before then stay with it (the T5 re-read).
//   request     the owner pays `poll` per item (across nodes: at most every `progress_every`); a request
//               travels half a ping-pong, waits for the victim's next poll (an idle victim answers at once), the reply
//               (second half of the list, and A1 on rank 0 paid by the victim) travels the other half.
//   central     a fetch-and-op on rank 0 per grain of N/(100P) items.
//   static      round robin, no communication; static-space: contiguous blocks of ids (regions of space). With
//               threads > 1 a rank's threads share its items perfectly (no cost, no granularity): generous.
//   flat        rma, request and central at ranks x threads run one rank per worker (MPI everywhere).
//   hier        ranks x `threads` workers (hierarchical_rank.hpp): a worker runs its local list (`local_claim` per
//               item), refills it with a chunk of the rank list under the rank's mutex (`rank_lock` + `claim` per
//               item; chunk = `chunk_us` by the last frame's costs, unknown items as refill_budget.hpp says, at
//               most 256 items), then steals half of a sibling's local list (`local_steal`); worker 0, once
//               every sibling is dry, leaves the global count (A2) and runs the rma thief above against other
//               ranks' lists, installing the share into its rank list; the others back off. Only worker 0 calls
//               into MPI (its progress calls, and the target of other ranks' operations is attentive only when
//               worker 0 is). A worker backing off
//               is woken when worker 0 installs a remote share and when the frame ends.
//               A worker other than 0 backs off at most sibling_backoff_cap_us(chunk_us) (idle_backoff.hpp).
//   hier-seeded hier whose next lists are contiguous blocks of equal predicted cost, each run heaviest first
//               (cost_seeded_lists.hpp: the last two frames' trend; the model knows the frames' costs exactly,
//               frontsteal-mpi measures them); refills are priced with the prediction.
//   termination A3 (a fetch-op read of rank 0's count) before every round of steal attempts; backoff as the
//               real idle loop (yield x3, then 1, 2, 4 ... 256 us).
//   contention  every atomic (fetch-op, CAS) on a rank's words occupies that rank for `atomic_service`
//               (one at a time): the central counter and the active count queue up at rank 0.
//   progress    with needs_target_progress (TCP without asynchronous progress) an operation aimed at a busy
//               rank is served only at that rank's next progress call (an item boundary at least
//               `progress_every` after the previous call, owner_progress.hpp); an idle rank is inside MPI
//               calls and serves at once.
//   frame end   a barrier: 2 log2(P) one-way messages.
//   LIFELINES   (hier, Workload::lifelines, lifelines.hpp; Saraswat et al., PPoPP'11, as invitations) rank r's
//   lifelines are
//               the ranks (r + 2^k) mod P, k < ceil(log2 P): a strongly connected graph of diameter <= log2 P.
//               A dry rank tries one round of random victims; if it gets nothing it registers at each lifeline
//               (a put each), reads the global count (A3) and waits on its own words, making no remote traffic.
//               Worker 0 of a rank whose rank list holds >= 2 items finds its registered hungry ranks at its
//               next item boundary, clears them and invites each (a put): the invited rank steals from it with
//               core's protocol (one directed attempt; if it fails, it registers again). The count's zero is
//               found by the rank whose A2 made it (every A2 is followed by its rank's A3), which tells rank 0
//               and its children in the binomial tree of puts rooted at rank 0, each rank forwarding to its own
//               (at most log2 P + 1 hops): no waiting rank polls rank 0. Without lifelines
//               (--lifelines off): rounds of random victims with back-off, each after an A3.
//   BATCH CLAIMS (hier, Workload::batch_claims, on by default as in frontsteal-mpi --batch-claims) a refill holds
//               the rank mutex for one owner claim per run of consecutive ids of its chunk (core's
//               Owner::try_claim_up_to: Front advanced by n in one O1-O4, bounded by a list entry); off, one per
//               item.
// LOSS ACCOUNT (hier): every worker's time is split into work (item costs), claims (per-item claims, progress
// calls, rank-list refills under the mutex), local steals, remote steals (worker 0's one-sided operations,
// termination reads included), idle (back-off), the tail (finished before the frame's slowest worker) and the
// frame-end barrier; the largest part that is not work is the model's bottleneck.
// NOT MODELLED: network bandwidth and topology (every pair is the calibrated pair), the OS scheduler (one
// rank per core), cache effects of stolen items, a rank's own contention between its thief and owner roles, and
// a waiting rank's probe rounds (hierarchical_rank.hpp: after 1 ms of waiting, for a donor the OS stopped).
//
// AUDIT. Every simulated frame checks that each item ran exactly once; Defect::kSkipReread (the thief keeps
// [mid, end) without the T5 re-read) must be caught — the model's negative control. Defect::kEmptyShare (a
// thief plans to take nothing: mid = end) is the control of the tests that say stealing happens and pays. Under
// hier every worker must also have finished (learned the frame is over) when the events run out;
// Defect::kLifelineDropsNotice (the rank that reads the count at 0 tells no other rank) must be caught there.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "distributed/synthetic_cost.hpp"
#include "reporting/json.hpp"

namespace frontsteal::mpi::sim {

// Nanoseconds. A one-sided operation's latency is its round trip (operation + MPI_Win_flush) to an attentive
// target, as --calibrate measures it.
struct Latencies {
  std::string source;  // where the numbers come from (file, transport)
  double get = 0, put = 0, cas = 0, fetch_op = 0;
  double ping_pong = 0;       // a 4-byte MPI_Send/MPI_Recv round trip
  double claim = 0;           // the rma owner's O1-O4
  double poll = 0;            // the request owner's MPI_Iprobe
  double progress_call = 0;   // the rma owner's progress call (owner_progress.hpp)
  double atomic_service = 0;  // time one atomic holds its home rank (see contention above)
  bool needs_target_progress = false;
  double progress_every = 50000;  // with needs_target_progress: the owner's call/poll interval (auto: 50 us)
  // Inside a rank (hier), over std atomics on one node. ASSUMED, not calibrated: frontsteal-mpi --calibrate
  // measures one-sided operations only; frontsteal-mpi-simulate --local-steal-ns sets the one that matters.
  double local_claim = 20;    // core's owner claim
  double local_steal = 1000;  // a sibling steal, the thief's whole protocol (lock, reads, publish, re-read)
  double rank_lock = 100;     // hier's rank mutex taken and released, uncontended
};

// Reads frontsteal-mpi --calibrate --json output (contents "calibration"); throws naming the file and the
// operation it lacks. atomic_service: with needs_target_progress, the per-operation time of 64 pipelined
// fetch-and-ops (the target's progress engine applies each in turn; an upper bound on its service); on
// shared memory, and for a calibration without that row, max(fetch_op - get, 50 ns): what an atomic costs
// beyond a plain get. Over TCP that difference of two ~40 us latencies changed sign between runs.
Latencies latencies_from_calibration(const std::string& path);

enum class Scheduler : std::uint8_t { kRma, kRequest, kCentral, kStatic, kStaticSpace, kHier, kHierSeeded };
const char* to_string(Scheduler s) noexcept;

enum class Defect : std::uint8_t { kNone, kSkipReread, kEmptyShare, kLifelineDropsNotice };

struct Workload {
  CostShape shape = CostShape::kSkewed;
  std::uint32_t items = 200000;
  double light_ns = 2000;
  std::uint32_t skew = 20;
  int frames = 5;
  int threads = 1;           // hier: workers per rank (the other schedulers: one per rank)
  double chunk_us = 50;      // hier: a refill is about this much work (frontsteal-mpi --chunk-us)
  bool lifelines = true;     // hier: LIFELINES below (frontsteal-mpi --lifelines, on by default)
  bool batch_claims = true;  // hier: BATCH CLAIMS below (frontsteal-mpi --batch-claims, on by default)
};

// Where the workers' time went (hier; ns summed over every worker and frame): see LOSS ACCOUNT above.
struct LossAccount {
  double work = 0, claims = 0, local_steals = 0, remote_steals = 0, idle = 0, tail = 0, barrier = 0;
  double total() const { return work + claims + local_steals + remote_steals + idle + tail + barrier; }
  // The largest part that is not work ("claims", "local steals", ...), and its share of the total.
  std::pair<const char*, double> bottleneck() const;
};

struct Result {
  Scheduler scheduler = Scheduler::kStatic;
  int ranks = 0;
  int threads = 1;        // workers per rank
  double time_ns = 0;     // all frames
  double work_ns = 0;     // sum of item costs, all frames
  double efficiency = 0;  // work / (ranks x threads x time)
  // The same over the frames after the first: lists carried over (§4.2.1), the steady state a frame loop runs in;
  // the first frame starts from contiguous blocks. 0 with one frame.
  double efficiency_carried = 0;
  std::vector<double> frame_ns;  // each frame's time, its barrier included
  std::uint64_t steals = 0, steal_attempts = 0, remote_operations = 0, local_steals = 0;
  double mean_steal_ns = 0;   // remote steals
  LossAccount loss;           // hier only
  bool exactly_once = true;   // the audit (every item once; hier: every worker learned the frame was over)
  std::string audit_failure;  // the first failure, when not
};

Result simulate(Scheduler s, int ranks, const Workload& w, const Latencies& lat, std::uint64_t seed = 1,
                Defect defect = Defect::kNone);

// What no scheduler of whole items can beat on this workload with `workers` workers and free communication,
// summed over the frames (efficiency = work / (workers x time), as Result's):
//   bound       each frame takes at least max(its work / workers, its largest item): the workload's own limit;
//   greedy      every item, in id order, to the first free worker (a central queue of grain 1 at no cost: what
//               a dynamic scheduler that knows no costs approaches);
//   lpt         longest item first to the first free worker (Graham's LPT: clairvoyant, within 4/3 of optimal).
// Not a model of any scheduler's overheads: a ceiling for all of them.
struct WorkloadLimits {
  int workers = 0;
  double max_item_ns = 0;  // the largest item of any frame
  double bound = 0, greedy = 0, lpt = 0;
};
WorkloadLimits workload_limits(const Workload& w, int workers);
// The same for given item costs (ns), one vector per frame.
WorkloadLimits workload_limits(const std::vector<std::vector<double>>& frame_costs, int workers);

report::Json latencies_json(const Latencies& lat);
// --plots DIR: efficiency against ranks (log scale), one line per latency set and scheduler, labelled
// SIMULATED; `rows` as in the --json document, `subtitle` the workload. Throws naming a file it cannot write.
void write_efficiency_plot(const std::string& dir, const report::Json& rows, const std::string& subtitle);
// --plots DIR with hier rows: where the workers' time went (the LOSS ACCOUNT), one stacked bar per latency set,
// scheduler, ranks and threads; `losses` as the --json document's "hier_loss_shares". Throws as above.
void write_loss_plot(const std::string& dir, const report::Json& losses, const std::string& subtitle);

}  // namespace frontsteal::mpi::sim
