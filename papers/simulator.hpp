// simulator.hpp — trace-driven discrete-event models of the schedulers, for more processors than the machine has.
//
// A model replays a cost trace (cost_trace.hpp): item i of frame f takes cost_ns[f][i] on any worker (the
// serial loop's time: no cache or memory-bandwidth effects of P cores sharing a machine are modelled). On top
// of the item costs each model charges what its scheduler does, in the calibrated costs of calibration.hpp:
//
//   static     (round robin, spatial partition) each worker runs its fixed list; per item `item_static`.
//   queue      one lock over a cursor, grain N/(100P) (paper §4.1). A worker that asks for a free lock gets
//              it at once and holds it `lock_uncontended` (+ one line transfer when the last holder was another
//              worker); one that finds it held sleeps, is woken by the release and asks again lock_wake_ns
//              later, holding it `lock_handoff` when it gets it. Requests are served in time order. Per item
//              `item_queue`.
//   stealing   the core protocol (§4.2): lists carried from frame to frame (each worker's next list = the items
//              it ran, in id order; the first frame: contiguous blocks). The owner claims an item at the
//              instant it starts it (per item `item_stealing`). An idle worker visits victims in its own
//              random order: a LockList held by another thief costs one line transfer (`steal_busy`); an empty
//              list two (`steal_empty`); a steal lowers the victim's End at once, holds the victim's LockList
//              for `steal`; the thief installs the share (stealable only from then on, else two idle
//              workers could pass one item back and forth forever) and starts it when the steal ends. After a full
//              round without a share the thief pauses `idle_round`. It stops when no unclaimed item is left anywhere.
//   chase-lev  lazy binary splitting from contiguous blocks every frame; an idle worker steals the oldest
//              (largest) range of a random victim for `steal_chase_lev`; two thieves on one victim within that
//              time: the later one loses the CAS (`steal_busy`). Per item `item_chase_lev`.
// Every model adds the per-frame cost of waking and joining P workers (Overheads::frame_ns), and starts worker w
// its frame w × wake_skew_ns late (notify_all wakes the sleepers one after another).
// Cache affinity: an item run by another worker than the one that ran it in the previous frame costs
// (1 + affinity_penalty) × its traced cost (the first frame has no previous worker: no penalty). Interference:
// worker w's item costs are multiplied by worker_slowdown[w] (a co-runner sharing its core).
// A waiter on the queue's lock sleeps: it asks again lock_wake_ns after the holder let it go, and a running
// worker may take the lock before it (glibc's mutex barges; a model that reserved the lock for the sleeper
// made the queue collapse beyond P = 2 — 3.8 frames/s at P = 32 against 83 at P = 1 — with this VM's 50 us
// wake-ups, an artefact of the model, not of the lock).
// Each simulated frame is audited: every item exactly once (the negative control plants a lost update).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "papers/calibration.hpp"
#include "papers/cost_trace.hpp"
#include "schedulers/static_scheduler.hpp"

namespace frontsteal::papers {

enum class Model { static_list, queue, stealing, chase_lev };

struct SimulationOptions {
  Model model = Model::stealing;
  WorkerId workers = 2;
  const sched::Assignment* assignment = nullptr;  // static_list: the lists (required)
  std::uint64_t seed = 1;                         // victim orders
  bool plant_lost_steal = false;          // negative control: a thief copies a share but never lowers the victim's End
  std::vector<double> worker_slowdown{};  // per worker, ≥ 1: item costs × this (empty: 1 for every worker)
  bool plant_ignore_affinity = false;     // negative control: the affinity penalty is never charged
};

// A simulated frame's loss account (schedulers/main_job/loss_account.hpp's terms, as far as the model has
// them), summed over frames and workers, in ns: work (the items' traced costs, with the affinity penalty and any
// slowdown), claim (the model's per-item cost and a queue's lock holds), checks (the harness's per-item checks),
// wake (release → the worker's first item), search (failed attempts and lock waits before work was found), steal
// (successful steals), termination (the worker's last item → the frame's end: the last, failed search and the
// join). available = frame x P; the terms add up to it.
struct SimulatedAccount {
  double work = 0, claim = 0, checks = 0, wake = 0, search = 0, steal = 0, termination = 0, available = 0;
  double share(double term) const { return available > 0 ? term / available : 0; }
};

struct SimulatedRun {
  SimulatedAccount account;
  double path_ns = 0;
  std::vector<double> frame_ns;
  double frames_per_s = 0;
  double utilization_pct = 0;  // Σ item costs / Σ (frame × P)
  double imbalance_mean = 0;   // max/mean busy per frame
  std::uint64_t steals = 0, failed_steals = 0, lock_waits = 0;
  std::uint64_t affinity_misses = 0;  // item runs on another worker than in the previous frame (after frame 0)
  double affinity_penalty_ns = 0;     // what those cost beyond their traced cost
  std::uint64_t audit_failures = 0;   // frames in which some item did not run exactly once
};

SimulatedRun simulate(const CostTrace& trace, const Overheads& overheads, const SimulationOptions& options);

}  // namespace frontsteal::papers
