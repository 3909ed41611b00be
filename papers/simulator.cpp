// simulator.cpp — the discrete-event models of simulator.hpp.
//
// Each model is a loop over events (time, worker) in time order (papers/simulation/event_queue.hpp); an event
// is the instant a worker does its next shared-memory step (claim an item, ask for the lock, try a victim).
// Between events a worker only runs items, so shared state changes only at event instants and the models need
// no finer clock. The audit, the stealing lists and the split are the simulation core's, shared with the MPI
// model (distributed/rma_simulator.cpp).
#include "papers/simulator.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>

#include "papers/simulation/event_queue.hpp"
#include "papers/simulation/exactly_once_audit.hpp"
#include "papers/simulation/stealing_lists.hpp"

namespace frontsteal::papers {
namespace {

// Workers woken together start in id order (notify_all), so ties go to the lower worker.
struct EventQueue : simulation::EventQueue<WorkerId> {
  EventQueue() : simulation::EventQueue<WorkerId>(simulation::Ties::kByWorker) {}
};

// What an item costs on a worker: its traced cost, the affinity penalty when another worker ran it in the
// previous frame, times the worker's slowdown. One per frame; `previous` is updated between frames.
struct ItemCharge {
  const std::vector<double>& cost;
  const std::vector<WorkerId>& previous;  // per item: the worker of the previous frame, or kNoWorker
  double penalty = 0;
  const std::vector<double>& slowdown;  // per worker (empty: 1)
  SimulatedRun& totals;
  static constexpr WorkerId kNoWorker = ~WorkerId{0};

  double operator()(ItemId id, WorkerId w) const {
    double c = cost[id];
    if (previous[id] != kNoWorker && previous[id] != w) {
      ++totals.affinity_misses;
      totals.affinity_penalty_ns += penalty * c;
      c *= 1 + penalty;
    }
    return slowdown.empty() ? c : c * slowdown[w];
  }
};

// What every model reports for one frame, per worker where it is a vector.
struct FrameOutcome {
  double last_finish_ns = 0;
  std::vector<double> busy_ns;           // item costs it ran
  std::vector<std::vector<ItemId>> ran;  // the items it ran, in order
  std::vector<double> start_ns;          // its first event (the wake-up)
  std::vector<double> last_end_ns;       // the end of its last item (its start when it ran none)
  std::vector<double> claim_ns;          // per-claim costs beyond the per-item cost (a queue's lock holds)
  std::vector<double> search_ns;         // failed attempts and lock waits before it found work
  std::vector<double> steal_ns;          // successful steals
  void resize(WorkerId p) {
    busy_ns.assign(p, 0);
    ran.assign(p, {});
    start_ns.assign(p, 0);
    last_end_ns.assign(p, 0);
    claim_ns.assign(p, 0);
    search_ns.assign(p, 0);
    steal_ns.assign(p, 0);
  }
  // Worker w starts at `at` (its first event).
  void start(WorkerId w, double at) { start_ns[w] = last_end_ns[w] = at; }
};

// The per-item overhead a model charges: its scheduler's claim and the harness's checks.
double item_overhead(const ModelCosts& mc, const Overheads& o) { return mc.item_ns + o.checks_ns; }

FrameOutcome run_static(const ItemCharge& cost, const sched::Assignment& lists, const ModelCosts& mc,
                        const Overheads& o) {
  FrameOutcome out;
  out.resize(static_cast<WorkerId>(lists.size()));
  out.ran = lists;
  for (std::size_t w = 0; w < lists.size(); ++w) {
    double t = o.wake_of(static_cast<unsigned>(w));
    out.start(static_cast<WorkerId>(w), t);
    for (ItemId id : lists[w]) {
      const double c = cost(id, static_cast<WorkerId>(w));
      out.busy_ns[w] += c;
      t += c + item_overhead(mc, o);
    }
    out.last_end_ns[w] = t;
    out.last_finish_ns = std::max(out.last_finish_ns, t);
  }
  return out;
}

FrameOutcome run_queue(const ItemCharge& cost, WorkerId p, const Overheads& o, SimulatedRun& totals) {
  const auto n = static_cast<ItemId>(cost.cost.size());
  const ItemId grain = sched::default_grain(n, p);
  FrameOutcome out;
  out.resize(p);
  EventQueue events;
  for (WorkerId w = 0; w < p; ++w) {
    events.push(o.wake_of(w), w);
    out.start(w, o.wake_of(w));
  }
  std::vector<double> waiting_since(p, -1);  // [w]: when w found the lock held (its wait is search once granted)
  ItemId cursor = 0;
  double free_at = 0;
  WorkerId last_holder = p;       // none yet
  std::vector<char> woken(p, 0);  // [w]: w slept on the lock since its last claim
  while (!events.empty()) {
    const auto e = events.pop();
    if (cursor >= n) {  // the worker takes the lock once more, finds the queue empty and leaves
      out.last_finish_ns = std::max(out.last_finish_ns, e.at);
      continue;
    }
    if (free_at > e.at) {
      // Held: the worker sleeps in the futex; the holder's unlock (at free_at) wakes it, and it runs again
      // lock_wake_ns later and asks again. The lock is not reserved for it meanwhile: glibc's mutex lets a
      // running worker take it first (barging), so a slow wake-up delays the sleeper, not the queue.
      ++totals.lock_waits;
      woken[e.worker] = 1;
      if (waiting_since[e.worker] < 0) waiting_since[e.worker] = e.at;
      events.push(free_at + o.lock_wake_ns, e.worker);
      continue;
    }
    const double granted = e.at;
    if (waiting_since[e.worker] >= 0) {
      out.search_ns[e.worker] += granted - waiting_since[e.worker];
      waiting_since[e.worker] = -1;
    }
    const double hold = woken[e.worker] ? o.lock_handoff_ns
                                        : o.lock_uncontended_ns +
                                              (last_holder != p && last_holder != e.worker ? o.line_transfer_ns : 0);
    woken[e.worker] = 0;
    free_at = granted + hold;
    last_holder = e.worker;
    const ItemId first = cursor;
    cursor = std::min<ItemId>(n, cursor + grain);
    out.claim_ns[e.worker] += hold;
    double t = granted + hold;
    for (ItemId id = first; id < cursor; ++id) {
      const double c = cost(id, e.worker);
      out.busy_ns[e.worker] += c;
      out.ran[e.worker].push_back(id);
      t += c + item_overhead(o.queue, o);
    }
    out.last_end_ns[e.worker] = t;
    events.push(t, e.worker);
  }
  return out;
}

// A failed steal attempt (busy or empty victim): its cost, plus the idle pause after a whole round of failures.
double failed_attempt(double cost, WorkerId& failures_in_round, WorkerId p, const Overheads& o, SimulatedRun& totals) {
  ++totals.failed_steals;
  if (++failures_in_round >= p - 1) {
    failures_in_round = 0;
    cost += o.idle_round_ns;
  }
  return cost;
}

// The stealing protocol's state that survives frames: each worker's list.
struct StealingState {
  std::vector<std::vector<ItemId>> lists;
  std::vector<std::vector<WorkerId>> victim_orders;
};

FrameOutcome run_stealing(const ItemCharge& cost, StealingState& state, const Overheads& o, bool plant_lost_steal,
                          SimulatedRun& totals) {
  const auto p = static_cast<WorkerId>(state.lists.size());
  struct Worker {
    std::vector<ItemId> list;
    std::size_t front = 0, end = 0;
    std::vector<ItemId> share;  // a steal in progress: installed (and stealable) only when the steal ends
    std::size_t next_victim = 0;
    WorkerId failures_in_round = 0;
    double lock_free_at = 0;  // this worker's LockList is held by a thief until then
  };
  std::vector<Worker> ws(p);
  std::int64_t unclaimed = 0;
  for (WorkerId w = 0; w < p; ++w) {
    ws[w].list = state.lists[w];
    ws[w].end = ws[w].list.size();
    unclaimed += static_cast<std::int64_t>(ws[w].end);
  }
  FrameOutcome out;
  out.resize(p);
  std::vector<double> pending_search(p, 0);  // [w]: failed attempts since w's last item (search once it steals)
  EventQueue events;
  for (WorkerId w = 0; w < p; ++w) {
    events.push(o.wake_of(w), w);
    out.start(w, o.wake_of(w));
  }
  while (!events.empty()) {
    const auto e = events.pop();
    Worker& me = ws[e.worker];
    if (!me.share.empty()) {  // the steal is over: install the share, as the protocol does after unlocking
      me.list.swap(me.share);
      me.share.clear();
      me.front = 0;
      me.end = me.list.size();
    }
    if (me.front < me.end) {  // owner: claim the item at Front and run it
      const ItemId id = me.list[me.front++];
      --unclaimed;
      const double c = cost(id, e.worker);
      out.busy_ns[e.worker] += c;
      out.ran[e.worker].push_back(id);
      out.last_end_ns[e.worker] = e.at + c + item_overhead(o.stealing, o);
      events.push(out.last_end_ns[e.worker], e.worker);
      continue;
    }
    if (unclaimed <= 0 || p == 1) {  // every list is empty: the worker is done
      out.last_finish_ns = std::max(out.last_finish_ns, e.at);
      continue;
    }
    const std::vector<WorkerId>& order = state.victim_orders[e.worker];
    Worker& victim = ws[order[me.next_victim++ % order.size()]];
    if (victim.lock_free_at > e.at || victim.front >= victim.end) {
      const double cost = victim.lock_free_at > e.at ? o.steal_busy_ns() : o.steal_empty_ns();
      const double spent = failed_attempt(cost, me.failures_in_round, p, o, totals);
      pending_search[e.worker] += spent;
      events.push(e.at + spent, e.worker);
    } else {  // steal the second half; End is lowered at once, the share is ours when the steal's time is over
      const std::size_t mid = simulation::steal_mid(victim.front, victim.end);
      me.share.assign(victim.list.begin() + static_cast<std::ptrdiff_t>(mid),
                      victim.list.begin() + static_cast<std::ptrdiff_t>(victim.end));
      if (!plant_lost_steal) victim.end = mid;
      victim.lock_free_at = e.at + o.steal_ns();
      me.failures_in_round = 0;
      ++totals.steals;
      out.search_ns[e.worker] += pending_search[e.worker];
      pending_search[e.worker] = 0;
      out.steal_ns[e.worker] += o.steal_ns();
      events.push(e.at + o.steal_ns(), e.worker);
    }
  }
  return out;
}

FrameOutcome run_chase_lev(const ItemCharge& cost, WorkerId p, const Overheads& o, std::mt19937_64& rng,
                           SimulatedRun& totals) {
  const auto n = static_cast<ItemId>(cost.cost.size());
  struct Worker {
    std::vector<IdRange> deque;  // [top, size): top = oldest (largest)
    std::size_t top = 0;
    IdRange running{0, 0};
    IdRange stolen{0, 0};  // a steal in progress: pushed onto the deque when the steal ends
    WorkerId failures_in_round = 0;
    double top_busy_until = 0;  // a thief's CAS on top is in flight until then
  };
  std::vector<Worker> ws(p);
  for (WorkerId w = 0; w < p; ++w) {
    const auto lo = static_cast<ItemId>(std::uint64_t{n} * w / p);
    const auto hi = static_cast<ItemId>(std::uint64_t{n} * (w + 1) / p);
    if (hi > lo) ws[w].deque.push_back({lo, hi});
  }
  std::int64_t remaining = n;
  FrameOutcome out;
  out.resize(p);
  std::vector<double> pending_search(p, 0);
  EventQueue events;
  for (WorkerId w = 0; w < p; ++w) {
    events.push(o.wake_of(w), w);
    out.start(w, o.wake_of(w));
  }
  std::uniform_int_distribution<WorkerId> other(0, p > 1 ? p - 2 : 0);
  while (!events.empty()) {
    const auto e = events.pop();
    Worker& me = ws[e.worker];
    if (!me.stolen.empty()) {
      me.deque.push_back(me.stolen);
      me.stolen = {0, 0};
    }
    if (me.running.begin < me.running.end) {
      const ItemId id = me.running.begin++;
      --remaining;
      const double c = cost(id, e.worker);
      out.busy_ns[e.worker] += c;
      out.ran[e.worker].push_back(id);
      out.last_end_ns[e.worker] = e.at + c + item_overhead(o.chase_lev, o);
      events.push(out.last_end_ns[e.worker], e.worker);
      continue;
    }
    if (me.top < me.deque.size()) {  // take the newest range, split off upper halves down to one item
      IdRange r = me.deque.back();
      me.deque.pop_back();
      while (r.end - r.begin > 1) {
        const ItemId mid = r.begin + (r.end - r.begin) / 2;
        me.deque.push_back({mid, r.end});
        r.end = mid;
      }
      me.running = r;
      events.push(e.at, e.worker);
      continue;
    }
    me.deque.clear();
    me.top = 0;
    if (remaining <= 0 || p == 1) {
      out.last_finish_ns = std::max(out.last_finish_ns, e.at);
      continue;
    }
    WorkerId v = other(rng);
    if (v >= e.worker) ++v;
    Worker& victim = ws[v];
    if (victim.top >= victim.deque.size() || victim.top_busy_until > e.at) {
      const double cost = victim.top >= victim.deque.size() ? o.steal_empty_ns() : o.steal_busy_ns();
      const double spent = failed_attempt(cost, me.failures_in_round, p, o, totals);
      pending_search[e.worker] += spent;
      events.push(e.at + spent, e.worker);
    } else {
      me.stolen = victim.deque[victim.top++];
      victim.top_busy_until = e.at + o.steal_chase_lev_ns();
      me.failures_in_round = 0;
      ++totals.steals;
      out.search_ns[e.worker] += pending_search[e.worker];
      pending_search[e.worker] = 0;
      out.steal_ns[e.worker] += o.steal_chase_lev_ns();
      events.push(e.at + o.steal_chase_lev_ns(), e.worker);
    }
  }
  return out;
}

}  // namespace

SimulatedRun simulate(const CostTrace& trace, const Overheads& o, const SimulationOptions& opt) {
  const auto n = static_cast<ItemId>(trace.surfaces());
  const WorkerId p = opt.workers;
  if (p == 0) throw std::invalid_argument("simulate: at least one worker");
  if (!opt.worker_slowdown.empty() && opt.worker_slowdown.size() != p) {
    throw std::invalid_argument("simulate: worker_slowdown needs one factor per worker");
  }
  if (opt.model == Model::static_list) {
    if (!opt.assignment) throw std::invalid_argument("simulate: the static model needs an assignment");
    sched::require_partition(*opt.assignment, p, n);
  }
  SimulatedRun run;
  StealingState stealing;
  if (opt.model == Model::stealing) {
    std::mt19937_64 rng(opt.seed);
    stealing.lists = simulation::contiguous_blocks(n, p);
    for (WorkerId w = 0; w < p; ++w) stealing.victim_orders.push_back(simulation::victim_order(w, p, rng));
  }
  std::mt19937_64 chase_rng(opt.seed);
  double busy_total = 0, available = 0, imbalance_sum = 0;
  simulation::ExactlyOnceAudit audit(n);
  std::vector<WorkerId> previous(n, ItemCharge::kNoWorker);
  const double penalty = opt.plant_ignore_affinity ? 0.0 : o.affinity_penalty;
  for (std::size_t f = 0; f < trace.frames(); ++f) {
    const ItemCharge cost{trace.cost_ns[f], previous, penalty, opt.worker_slowdown, run};
    FrameOutcome fo;
    const ModelCosts* mc = nullptr;
    switch (opt.model) {
      case Model::static_list:
        fo = run_static(cost, *opt.assignment, o.static_list, o);
        mc = &o.static_list;
        break;
      case Model::queue:
        fo = run_queue(cost, p, o, run);
        mc = &o.queue;
        break;
      case Model::stealing:
        fo = run_stealing(cost, stealing, o, opt.plant_lost_steal, run);
        mc = &o.stealing;
        break;
      case Model::chase_lev:
        fo = run_chase_lev(cost, p, o, chase_rng, run);
        mc = &o.chase_lev;
        break;
    }
    const double frame = fo.last_finish_ns + (o.account_model() ? o.join_ns : o.frame_ns(*mc, p));
    run.frame_ns.push_back(frame);
    for (WorkerId w = 0; w < p; ++w) {
      const auto items = static_cast<double>(fo.ran[w].size());
      SimulatedAccount& a = run.account;
      a.work += fo.busy_ns[w];
      a.claim += items * mc->item_ns + fo.claim_ns[w];
      a.checks += items * o.checks_ns;
      a.wake += fo.start_ns[w];
      a.search += fo.search_ns[w];
      a.steal += fo.steal_ns[w];
      a.termination += frame - fo.last_end_ns[w];
      a.available += frame;
    }
    run.path_ns += frame;
    const double busy = std::accumulate(fo.busy_ns.begin(), fo.busy_ns.end(), 0.0);
    busy_total += busy;
    available += frame * p;
    const double mean = busy / p;
    imbalance_sum += mean > 0 ? *std::max_element(fo.busy_ns.begin(), fo.busy_ns.end()) / mean : 1.0;
    audit.clear();
    for (const auto& list : fo.ran) audit.count(list);
    if (audit.first_failure()) ++run.audit_failures;
    for (WorkerId w = 0; w < p; ++w) {
      for (ItemId id : fo.ran[w]) previous[id] = w;
    }
    if (opt.model == Model::stealing) stealing.lists = simulation::lists_from_runs(fo.ran, n);
  }
  run.frames_per_s = run.path_ns > 0 ? 1e9 * static_cast<double>(trace.frames()) / run.path_ns : 0;
  run.utilization_pct = available > 0 ? 100.0 * busy_total / available : 0;
  run.imbalance_mean = trace.frames() ? imbalance_sum / static_cast<double>(trace.frames()) : 0;
  return run;
}

}  // namespace frontsteal::papers
