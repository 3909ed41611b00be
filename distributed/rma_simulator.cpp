// rma_simulator.cpp — the discrete-event model of rma_simulator.hpp. SIMULATED numbers only. The event queue,
// the exactly-once audit, the first lists, the victim orders and the split are the simulation core's
// (papers/simulation/), shared with the shared-memory models (papers/simulator.cpp).
#include "distributed/rma_simulator.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <random>

#include "distributed/cost_seeded_lists.hpp"
#include "distributed/idle_backoff.hpp"
#include "distributed/refill_budget.hpp"
#include "distributed/synthetic_cost.hpp"
#include "papers/simulation/event_queue.hpp"
#include "papers/simulation/exactly_once_audit.hpp"
#include "papers/simulation/stealing_lists.hpp"

namespace frontsteal::mpi::sim {
namespace {

bool hier(Scheduler s) { return s == Scheduler::kHier || s == Scheduler::kHierSeeded; }

constexpr double kYieldNs = 1000;        // an idle loop's sched_yield on a loaded core (assumed)
constexpr double kInstallRetryNs = 500;  // a thief's install waits for its own LockList (held by a thief)
// lifelines: a waiting rank sees a word written into its window within this (assumed: it yields, then sleeps up to
// idle_backoff.hpp's kLifelineWaitCapUs).
constexpr double kLocalPollNs = 2000;
constexpr double kNever = std::numeric_limits<double>::infinity();

enum class Step : std::uint8_t { kOwner, kRoundStart, kTryVictim, kT1, kT2, kT3, kT4, kInstall, kAwaitReply, kDone };

// hier: the largest chunk a worker takes from its rank list at once, and the remote victims of one round
// (hierarchical_rank.cpp's kMaxChunk and kVictimsPerRound).
constexpr std::uint32_t kMaxChunk = 256;
constexpr std::size_t kVictimsPerRound = 8;

// The idle loop's back-off after `failed` fruitless rounds (idle_backoff.hpp): yields, then 1, 2, 4 ... 256 us.
double backoff_ns(std::uint32_t& failed) {
  ++failed;
  return failed < 4 ? kYieldNs : 1000.0 * (1u << std::min<std::uint32_t>(failed - 4, 8));
}

// What a hier worker is doing until its next event (the loss account's parts).
enum Part : std::uint8_t { kWork, kClaims, kLocalSteals, kRemoteSteals, kIdle, kParts };

// hier: one worker thread of a rank. Its local list is [front, end) of `list`.
struct Worker {
  std::vector<ItemId> list;
  std::uint32_t front = 0, end = 0, failed_rounds = 0;
  bool holding = false, done = false;
  double finish = 0, since = 0;
  double installed = 0;  // its list is visible to sibling thieves from this time (a share in flight is not)
  double next_at = 0;    // its one live event: an earlier one superseded by a wake-up is ignored
  Part pending = kIdle;
  double parts[kParts] = {};
  // refill_budget.hpp's memory of this frame; the item it is running (the model learns an item's time when it
  // ends, as the code does).
  RefillHistory history;
  double running_ns = 0;
  std::vector<std::uint32_t> siblings;  // local victims, in this worker's random order
};

struct Rank {
  std::vector<ItemId> list, executed, share;
  std::uint32_t front = 0, end = 0;
  bool busy = false, locked = false;
  double busy_until = 0, server_free = 0, finish = 0, steal_start = 0;
  double next_call = 0;  // the owner's next progress call / poll is due at or after this time (PollGate)
  Step step = Step::kOwner;
  std::vector<int> victims;
  std::size_t victim_index = 0, next_request = 0;
  std::size_t round_tried = 0;  // hier: victims tried in this round (at most kVictimsPerRound)
  std::uint32_t mid = 0, old_end = 0, front_read = 0, failed_rounds = 0;
  std::vector<std::pair<int, double>> pending;  // request: (thief, arrival)
  // hier: the rank list is [front, end) of `list` above; these are the rank's own.
  double mutex_free = 0;          // the rank mutex is free from this time on
  std::int64_t local_active = 0;  // workers holding work (the local active count)
  bool rank_active = true;        // counts in the global active count
  bool frame_over = false;        // worker 0 read the global count at 0
  // LIFELINES: this rank's lifelines ((r + 2^k) mod P), the ranks registered here (hungry_in[k]: rank
  // (r - 2^k) mod P), the rank that invited this one (its directed victim), and the frame-end notice's arrival.
  std::vector<int> lifelines;
  std::vector<char> hungry_in;
  int directed = -1;
  bool registered = false, waiting = false;
  double notice_at = kNever;
};

class Model {
 public:
  Model(Scheduler s, int p, const Workload& w, const Latencies& lat, std::uint64_t seed, Defect d)
      : s_(s),
        p_(p),
        w_(w),
        lat_(lat),
        defect_(d),
        cost_(w.shape, w.items, w.frames, w.skew),
        threads_(hier(s) || s == Scheduler::kStatic || s == Scheduler::kStaticSpace ? std::max(1, w.threads) : 1),
        ranks_(static_cast<std::size_t>(p)),
        audit_(w.items) {
    std::vector<std::vector<ItemId>> blocks = simulation::contiguous_blocks(w.items, static_cast<std::uint32_t>(p));
    for (int r = 0; r < p; ++r) {
      Rank& k = ranks_[static_cast<std::size_t>(r)];
      std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(r));
      k.victims = simulation::victim_order(r, p, rng);
      k.list = blocks[static_cast<std::size_t>(r)];
      for (int step = 1; step < p && w.lifelines && hier(s); step *= 2) k.lifelines.push_back((r + step) % p);
      k.hungry_in.assign(k.lifelines.size(), 0);
      for (int t = 0; t < threads_; ++t) {
        Worker x;
        x.siblings = simulation::victim_order(static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(threads_), rng);
        workers_.push_back(std::move(x));
      }
    }
    space_blocks_ = std::move(blocks);
  }

  Result run() {
    Result res;
    res.scheduler = s_;
    res.ranks = p_;
    res.threads = threads_;
    for (int f = 0; f < w_.frames && res.exactly_once; ++f) {
      frame_ = f;
      const bool fixed = s_ == Scheduler::kStatic || s_ == Scheduler::kStaticSpace;
      const double t = fixed ? static_frame() : event_frame();
      res.time_ns += t + barrier_ns();
      res.frame_ns.push_back(t + barrier_ns());
      if (hier(s_)) account_frame(res.loss, t);
      audit(res);
    }
    double later_work = 0;
    for (ItemId id = 0; id < w_.items; ++id) {
      for (int f = 0; f < w_.frames; ++f) {
        res.work_ns += cost(f, id);
        if (f > 0) later_work += cost(f, id);
      }
    }
    const double workers = static_cast<double>(p_) * threads_;
    res.efficiency = res.work_ns / (workers * res.time_ns);
    if (res.frame_ns.size() > 1) {
      res.efficiency_carried = later_work / (workers * (res.time_ns - res.frame_ns.front()));
    }
    res.local_steals = local_steals_;
    res.steals = steals_;
    res.steal_attempts = attempts_;
    res.remote_operations = remote_ops_;
    res.mean_steal_ns = steals_ ? steal_ns_ / static_cast<double>(steals_) : 0;
    return res;
  }

 private:
  double cost(int f, ItemId id) const { return cost_.units(f, id) * w_.light_ns; }
  double one_way() const { return lat_.ping_pong / 2; }
  double barrier_ns() const { return 2 * std::ceil(std::log2(std::max(2, p_))) * one_way(); }
  Rank& at(int r) { return ranks_[static_cast<std::size_t>(r)]; }

  // A round trip to `target` issued at t: served when it arrives, or at the target's next item boundary when
  // the transport needs target progress and the target is busy; atomics also queue at the target.
  double op(double t, int target, double latency, bool atomic) {
    ++remote_ops_;
    Rank& v = at(target);
    const double arrive = t + latency / 2;
    double start = arrive;
    // Served at the busy target's first progress call after arrival: its next item boundary once the gate
    // is due (approximated by max(boundary, gate): optimistic by less than one item).
    if (lat_.needs_target_progress && v.busy && std::max(v.busy_until, v.next_call) > arrive) {
      start = std::max(v.busy_until, v.next_call);
      // central: rank 0, the counter's home, calls into MPI at most every progress_every inside its chunks
      // (frame_runner.cpp); modelled as the worst case, one whole interval after arrival.
      if (s_ == Scheduler::kCentral && target == 0) start = std::min(v.busy_until, arrive + lat_.progress_every);
    }
    if (atomic) {
      start = std::max(start, v.server_free);
      v.server_free = start + lat_.atomic_service;
    }
    return start + latency / 2;
  }
  // Rank r's next step at t: under hier, its worker 0's (the only one that calls MPI).
  void at_time(double t, int r) {
    if (hier(s_)) return wake(t, r * threads_);
    events_.push(t, r * threads_);
  }
  // hier: rank r's workers backing off (not worker 0) take their next step at t (hierarchical_rank.cpp's notify).
  void wake_siblings(double t, int r) {
    for (int t2 = 1; t2 < threads_; ++t2) {
      const Worker& y = worker(r * threads_ + t2);
      if (!y.done && y.pending == kIdle && y.next_at > t) wake(t, r * threads_ + t2);
    }
  }
  // hier: worker `id`'s next event at t (replacing the one it had).
  void wake(double t, int id) {
    worker(id).next_at = t;
    events_.push(t, id);
  }

  double static_frame() {
    double worst = 0;
    for (int r = 0; r < p_; ++r) {
      double t = 0;
      at(r).executed.clear();
      if (s_ == Scheduler::kStaticSpace) {
        for (ItemId id : space_blocks_[static_cast<std::size_t>(r)]) {
          t += cost(frame_, id);
          at(r).executed.push_back(id);
        }
      } else {
        for (ItemId id = static_cast<ItemId>(r); id < w_.items; id += static_cast<ItemId>(p_)) {
          t += cost(frame_, id);
          at(r).executed.push_back(id);
        }
      }
      worst = std::max(worst, t / threads_);  // a rank's threads share its items perfectly: generous to static
    }
    return worst;
  }

  double event_frame() {
    active_ = p_;
    next_item_ = 0;
    events_ = Events(simulation::Ties::kInArrivalOrder);  // the event limit counts one frame
    if (s_ == Scheduler::kHierSeeded && frame_ > 0) seed_lists();
    for (int r = 0; r < p_; ++r) {
      Rank& k = at(r);
      if (s_ == Scheduler::kRma || s_ == Scheduler::kRequest) {
        if (frame_ > 0) k.list = k.executed;  // §4.2.1: next frame's list is what the rank processed
      }
      if (hier(s_)) start_hier_frame(r);
      k.executed.clear();
      k.front = 0;
      k.end = static_cast<std::uint32_t>(k.list.size());
      k.busy = k.locked = false;
      k.busy_until = k.server_free = k.finish = k.next_call = 0;
      k.failed_rounds = 0;
      k.pending.clear();
      k.step = Step::kOwner;
      for (int t = 0; t < threads_; ++t) hier(s_) ? wake(0, r * threads_ + t) : events_.push(0, r);
    }
    while (!events_.empty()) {
      const auto [t, id] = events_.pop();
      if (s_ == Scheduler::kCentral) {
        central_step(t, id);
      } else if (hier(s_)) {
        hier_event(t, id);
      } else {
        stealing_step(t, id);
      }
    }
    double worst = 0;
    for (int r = 0; r < p_; ++r) worst = std::max(worst, at(r).finish);
    return worst;
  }

  void central_step(double t, int r) {
    Rank& k = at(r);
    const std::uint64_t grain = std::max<std::uint64_t>(1, w_.items / (100ull * static_cast<std::uint64_t>(p_)));
    const double c = op(t, 0, lat_.fetch_op, true);
    const std::uint64_t s = next_item_;
    next_item_ += grain;
    if (s >= w_.items) {
      k.busy = false;
      k.finish = c;
      return;
    }
    double end = c;
    for (std::uint64_t id = s; id < std::min<std::uint64_t>(s + grain, w_.items); ++id) {
      end += cost(frame_, static_cast<ItemId>(id));
      k.executed.push_back(static_cast<ItemId>(id));
    }
    // Rank 0 pays a progress call per interval of its chunk where the transport needs them (frame_runner.cpp).
    if (r == 0 && lat_.needs_target_progress) {
      const double items = static_cast<double>(std::min<std::uint64_t>(s + grain, w_.items) - s);
      end += lat_.progress_call *
             (lat_.progress_every > 0 ? std::min(items, std::floor((end - c) / lat_.progress_every)) : items);
    }
    k.busy = true;
    k.busy_until = end;
    at_time(end, r);
  }

  // The request owner's poll at an item boundary (t): answers the requests that have arrived; with `all` (it
  // has just run out of work) also those still in flight, empty, as they arrive.
  double answer_pending(double t, Rank& victim, bool all) {
    for (auto it = victim.pending.begin(); it != victim.pending.end();) {
      if (it->second > t && !all) {
        ++it;
        continue;
      }
      Rank& thief = at(it->first);
      thief.share.clear();
      const std::uint32_t remaining = victim.end - victim.front;
      if (victim.busy && remaining >= 2) {
        const std::uint32_t keep = static_cast<std::uint32_t>(items_left_to_victim(remaining));
        thief.share.assign(victim.list.begin() + victim.front + keep, victim.list.begin() + victim.end);
        victim.end = victim.front + keep;
        t = op(t, 0, lat_.fetch_op, true);  // A1 on the thief's behalf, paid by the victim
        ++active_;
      }
      at_time(std::max(t, it->second) + one_way(), it->first);
      it = victim.pending.erase(it);
    }
    return t;
  }

  void become_idle(double t, int r) {
    Rank& k = at(r);
    k.busy = false;
    if (s_ == Scheduler::kRequest) t = answer_pending(t, k, true);
    --active_;  // A2
    k.step = Step::kRoundStart;
    at_time(op(t, 0, lat_.fetch_op, true), r);
  }

  void stealing_step(double t, int r) {
    Rank& k = at(r);
    switch (k.step) {
      case Step::kOwner: {
        // The gate (owner_progress.hpp's PollGate): across nodes the rma owner's progress call and the request
        // owner's poll happen at most every progress_every; on one node rma makes none, request polls always.
        const bool gated = lat_.needs_target_progress;
        const bool due = !gated || t >= k.next_call;
        if (gated && due) k.next_call = t + lat_.progress_every;
        if (s_ == Scheduler::kRequest && due && !k.pending.empty()) t = answer_pending(t, k, false);
        if (k.front >= k.end) return become_idle(t, r);
        const ItemId id = k.list[k.front++];
        k.executed.push_back(id);
        const double overhead =
            s_ == Scheduler::kRma ? lat_.claim + (gated && due ? lat_.progress_call : 0) : (due ? lat_.poll : 0);
        k.busy = true;
        k.busy_until = t + overhead + cost(frame_, id);
        return at_time(k.busy_until, r);
      }
      case Step::kRoundStart: {
        const double c = op(t, 0, lat_.fetch_op, true);  // A3
        if (active_ == 0) {
          k.step = Step::kDone;
          k.finish = c;
          if (hier(s_)) {
            k.frame_over = true;
            Worker& x = worker(r * threads_);
            x.parts[kRemoteSteals] += c - t;
            finish(x, k, c);
            wake_siblings(c, r);  // the frame's end reaches the workers backing off at once
            if (w_.lifelines && defect_ != Defect::kLifelineDropsNotice) tell_frame_over(c, r);
          }
          return;
        }
        if (k.registered) {  // LIFELINES: wait for an invitation or the frame's end, on this rank's own words
          k.waiting = true;
          worker(r * threads_).parts[kRemoteSteals] += c - t;
          worker(r * threads_).since = c;
          worker(r * threads_).pending = kIdle;
          // The notice is a word that stays set: one that arrived before the rank began to wait is read at once
          // (a thief that joined late, after the count's 0, can make this rank's A3 read 1: core's A1 note).
          if (k.notice_at < kNever) wake(std::max(c, k.notice_at), r * threads_);
          return;
        }
        if (!hier(s_)) k.victim_index = 0;  // hier: the next round continues where this one stopped
        k.round_tried = 0;
        if (s_ == Scheduler::kRequest) return send_request(c, r);
        k.step = Step::kTryVictim;
        return at_time(c, r);
      }
      case Step::kTryVictim: return try_victim(t, r);
      case Step::kT1: {
        k.front_read = victim(k).front;  // T1, with T2, the entry count and the entries: one view (V1)
        k.step = Step::kT2;
        return at_time(op(t, current(k), lat_.get, false), r);
      }
      case Step::kT2: {
        Rank& v = victim(k);
        const std::uint32_t end = v.end;  // T2
        if (k.front_read >= end) {
          v.locked = false;  // L3
          const double c = op(t, current(k), lat_.fetch_op, true);
          ++k.victim_index;
          k.step = Step::kTryVictim;
          return at_time(c, r);
        }
        k.mid = defect_ == Defect::kEmptyShare ? end : simulation::steal_mid(k.front_read, end);
        k.old_end = end;
        ++active_;  // A1
        const double c = op(t, 0, lat_.fetch_op, true);
        k.step = Step::kT3;
        return at_time(c, r);
      }
      case Step::kT3: {
        Rank& v = victim(k);
        const double c = op(t, current(k), lat_.put, false);
        v.end = k.mid;  // T3: from here the victim claims no item at or past mid
        const std::uint32_t first = defect_ == Defect::kSkipReread ? k.mid : std::max(k.mid, v.front);  // T5's re-read
        k.share.assign(v.list.begin() + std::min(first, k.old_end), v.list.begin() + k.old_end);
        k.step = Step::kT4;
        return at_time(c, r);
      }
      case Step::kT4: {
        double c = op(t, current(k), lat_.get, false);  // T4
        c = op(c, current(k), lat_.get, false);         // T5
        victim(k).locked = false;                       // L3
        k.step = Step::kInstall;
        return at_time(op(c, current(k), lat_.fetch_op, true), r);
      }
      case Step::kInstall: return install(t, r);
      case Step::kAwaitReply: {
        if (!k.share.empty()) {
          steal_ns_ += t - k.steal_start;
          return take_share(t, r);
        }
        k.step = Step::kRoundStart;
        return at_time(t + backoff(k), r);
      }
      case Step::kDone: return;
    }
  }

  int current(const Rank& k) const {
    if (k.directed >= 0) return k.directed;
    return k.victims[k.victim_index % k.victims.size()];
  }
  bool round_over(const Rank& k) const {
    if (k.directed >= 0) return k.round_tried >= 1;
    return hier(s_) ? k.round_tried >= std::min(kVictimsPerRound, k.victims.size())
                    : k.victim_index >= k.victims.size();
  }
  Rank& victim(const Rank& k) { return at(current(k)); }
  double backoff(Rank& k) { return backoff_ns(k.failed_rounds); }

  // ---- hier: ranks x threads (hierarchical_rank.hpp) ----
  Worker& worker(int id) { return workers_[static_cast<std::size_t>(id)]; }

  // hier-seeded: every rank's next list, a contiguous block of equal predicted cost run heaviest first
  // (cost_seeded_lists.hpp, frontsteal-mpi's code); the model knows the frames' costs exactly, frontsteal-mpi
  // measures them. The prediction also prices the refills.
  void seed_lists() {
    std::vector<float> last(w_.items), before;
    for (ItemId id = 0; id < w_.items; ++id) last[id] = static_cast<float>(cost(frame_ - 1, id));
    if (frame_ > 1) {
      before.resize(w_.items);
      for (ItemId id = 0; id < w_.items; ++id) before[id] = static_cast<float>(cost(frame_ - 2, id));
    }
    predicted_ = predicted_costs(last, before);
    const std::vector<RangeList> blocks = cost_balanced_blocks(predicted_, static_cast<WorkerId>(p_));
    for (int r = 0; r < p_; ++r) {
      Rank& k = at(r);
      k.list.clear();
      for (const IdRange& range : heavy_first(blocks[static_cast<std::size_t>(r)], predicted_)) {
        for (ItemId id = range.begin; id < range.end; ++id) k.list.push_back(id);
      }
    }
  }

  void start_hier_frame(int r) {
    Rank& k = at(r);
    if (frame_ > 0 && s_ == Scheduler::kHier) {  // the rank's next list: every item its workers ran, in id order
      k.list = k.executed;
      std::sort(k.list.begin(), k.list.end());
    }
    k.mutex_free = 0;
    k.local_active = 0;
    k.rank_active = true;
    k.frame_over = false;
    std::fill(k.hungry_in.begin(), k.hungry_in.end(), 0);
    k.directed = -1;
    k.registered = k.waiting = false;
    k.notice_at = kNever;
    for (int t = 0; t < threads_; ++t) {
      Worker& x = worker(r * threads_ + t);
      x.list.clear();
      x.front = x.end = x.failed_rounds = 0;
      x.holding = x.done = false;
      x.finish = x.since = x.installed = 0;
      x.history = {};
      x.running_ns = 0;
      x.pending = kIdle;
    }
  }

  void finish(Worker& x, Rank& k, double t) {
    x.done = true;
    x.finish = t;
    x.since = t;
    k.finish = std::max(k.finish, t);
  }

  void hier_event(double t, int id) {
    Worker& x = worker(id);
    if (t != x.next_at) return;  // superseded by a wake-up
    const int r = id / threads_;
    Rank& k = at(r);
    x.parts[x.pending] += t - x.since;  // what the worker did since its last event
    x.since = t;
    if (x.pending == kWork) {  // its item ended at t
      x.history.last_item_ns = x.running_ns;
      x.pending = kIdle;
    }
    if (x.done) return;
    if (t >= k.notice_at) k.frame_over = true;
    if (k.frame_over && x.front >= x.end) return finish(x, k, t);  // a worker still holding items runs them
    if (id % threads_ == 0 && k.step != Step::kOwner) {            // worker 0 inside a remote steal (the rma thief)
      x.pending = kRemoteSteals;
      return stealing_step(t, r);
    }
    hier_worker(t, r, id);
  }

  // A hier worker free at t: its local list, a chunk of the rank list, a sibling, or (worker 0, the rank dry)
  // another rank.
  void hier_worker(double t, int r, int id) {
    Worker& x = worker(id);
    Rank& k = at(r);
    const bool main_thread = id % threads_ == 0;
    if (x.front < x.end) {
      const ItemId item = x.list[x.front++];
      k.executed.push_back(item);
      const bool due = main_thread && lat_.needs_target_progress && t >= k.next_call;
      if (due) k.next_call = t + lat_.progress_every;
      if (main_thread && w_.lifelines && k.end >= k.front + 2) {  // a donor: its invitations' puts
        const double invited = invite_hungry(t, r);
        x.parts[kRemoteSteals] += invited - t;
        t = invited;
      }
      const double overhead = lat_.local_claim + (due ? lat_.progress_call : 0);
      const double c = cost(frame_, item);
      x.parts[kClaims] += overhead;
      x.since = t + overhead;
      x.pending = kWork;
      x.running_ns = c;
      if (main_thread) {
        k.busy = true;
        k.busy_until = t + overhead + c;
      }
      return wake(t + overhead + c, id);
    }
    if (main_thread) k.busy = false;
    if (x.holding) {  // A2 (local)
      --k.local_active;
      x.holding = false;
    }
    // A chunk of the rank list, claimed under the rank mutex: one owner claim per item, or with batch_claims one
    // per run of consecutive ids (the code's list entries are such runs, merged).
    const double start = std::max(t, k.mutex_free);
    const std::uint32_t n = chunk_worth(k, x, r);
    std::uint32_t claims = n;
    if (w_.batch_claims && n > 0) {
      claims = 1;
      for (std::uint32_t i = k.front + 1; i < k.front + n; ++i) claims += k.list[i] != k.list[i - 1] + 1 ? 1 : 0;
    }
    k.mutex_free = start + lat_.rank_lock + claims * lat_.claim;
    x.parts[kClaims] += k.mutex_free - t;
    t = x.since = k.mutex_free;
    if (n > 0) {
      x.history.last_refill = n;
      x.list.assign(k.list.begin() + k.front, k.list.begin() + k.front + n);
      k.front += n;
      return hold_local(x, k, t, id);
    }
    // Half of a sibling's local list.
    for (std::uint32_t v : x.siblings) {
      Worker& y = worker(r * threads_ + static_cast<int>(v));
      if (y.front >= y.end || y.installed > t) continue;
      const std::uint32_t mid = simulation::steal_mid(y.front, y.end);
      if (mid >= y.end) continue;
      x.list.assign(y.list.begin() + mid, y.list.begin() + y.end);
      y.end = mid;  // from here the sibling claims nothing at or past mid
      ++local_steals_;
      x.parts[kLocalSteals] += lat_.local_steal;
      t = x.since = t + lat_.local_steal;
      return hold_local(x, k, t, id);
    }
    // Nothing in the rank for this worker: worker 0 goes to other ranks once every sibling is dry.
    if (k.frame_over) return finish(x, k, t);
    if (!main_thread || k.local_active > 0) {
      x.pending = kIdle;
      return wake(t + std::min(backoff_ns(x.failed_rounds), 1000.0 * sibling_backoff_cap_us(w_.chunk_us)), id);
    }
    if (k.rank_active) {  // A2 for the rank
      k.rank_active = false;
      --active_;
      const double c = op(t, 0, lat_.fetch_op, true);
      x.parts[kRemoteSteals] += c - t;
      t = x.since = c;
    }
    x.pending = kRemoteSteals;
    k.step = Step::kRoundStart;
    stealing_step(t, r);
  }

  // The items of worker x's next refill from rank r's list (refill_budget.hpp, as hierarchical_rank.cpp's
  // refill): priced by the last frame's costs where the rank knows them (hier: the items it ran; hier-seeded:
  // every item, shared), the others as the budget says.
  std::uint32_t chunk_worth(const Rank& k, const Worker& x, int r) const {
    if (k.front >= k.end) return 0;  // a thief may set End below Front
    RefillBudget budget(w_.chunk_us * 1000, kMaxChunk, x.history, k.end - k.front,
                        static_cast<std::uint32_t>(threads_));
    std::uint32_t n = 0;
    while (k.front + n < k.end) {
      const ItemId id = k.list[k.front + n];
      double known = -1;
      if (s_ == Scheduler::kHierSeeded && !predicted_.empty()) {
        known = predicted_[id];
      } else if (frame_ > 0 && last_runner_[id] == r) {
        known = cost(frame_ - 1, id);
      }
      if (!budget.admit(known)) break;
      ++n;
    }
    return n;
  }

  // x now holds x.list (a chunk or a stolen half) from t: it counts in the local active count (A1, local), and
  // claims its first item.
  void hold_local(Worker& x, Rank& k, double t, int id) {
    x.front = 0;
    x.end = static_cast<std::uint32_t>(x.list.size());
    x.installed = t;
    x.holding = true;
    x.failed_rounds = 0;
    ++k.local_active;
    hier_worker(t, id / threads_, id);  // the owner claims its first item at once (wait-free), before any thief
  }

  // After a hier frame of length `frame`: each worker's parts, its tail and the barrier, into `loss`.
  void account_frame(LossAccount& loss, double frame) {
    for (Worker& x : workers_) {
      loss.work += x.parts[kWork];
      loss.claims += x.parts[kClaims];
      loss.local_steals += x.parts[kLocalSteals];
      loss.remote_steals += x.parts[kRemoteSteals];
      loss.idle += x.parts[kIdle];
      loss.tail += frame - x.finish;
      loss.barrier += barrier_ns();
      std::fill(std::begin(x.parts), std::end(x.parts), 0.0);
    }
  }

  void try_victim(double t, int r) {
    Rank& k = at(r);
    if (round_over(k)) {
      k.step = Step::kRoundStart;
      if (w_.lifelines && hier(s_)) return at_time(register_hungry(t, r), r);
      if (hier(s_)) worker(r * threads_).pending = kIdle;
      return at_time(t + backoff(k), r);
    }
    ++attempts_;
    ++k.round_tried;
    const double c = op(t, current(k), lat_.fetch_op, true);  // L2: the exchange (no L1 probe over RMA, V3)
    if (victim(k).locked) {
      ++k.victim_index;
      return at_time(c, r);
    }
    victim(k).locked = true;  // L2
    k.steal_start = t;
    k.step = Step::kT1;
    at_time(c, r);
  }

  void install(double t, int r) {
    Rank& k = at(r);
    if (k.share.empty()) {  // every planned item was claimed by the victim first: A2, next victim
      --active_;
      ++k.victim_index;
      k.step = Step::kTryVictim;
      return at_time(op(t, 0, lat_.fetch_op, true), r);
    }
    if (k.locked) return at_time(t + kInstallRetryNs, r);  // a thief holds our LockList: install waits (L2)
    steal_ns_ += t - k.steal_start;
    take_share(t, r);
  }

  void take_share(double t, int r) {
    Rank& k = at(r);
    ++steals_;
    if (hier(s_)) {
      k.rank_active = true;  // the share goes into the rank list (A1 came with it)
      wake_siblings(t, r);
    }
    k.list = k.share;
    k.share.clear();
    k.directed = -1;
    k.front = 0;
    k.end = static_cast<std::uint32_t>(k.list.size());
    k.failed_rounds = 0;
    k.step = Step::kOwner;
    at_time(t, r);
  }

  void send_request(double t, int r) {
    Rank& k = at(r);
    ++attempts_;
    k.share.clear();
    const int v = k.victims[k.next_request++ % k.victims.size()];
    k.steal_start = t;
    k.step = Step::kAwaitReply;
    if (at(v).busy) {
      at(v).pending.emplace_back(r, t + one_way());  // answered at the victim's next item boundary
    } else {
      at_time(t + 2 * one_way(), r);  // an idle victim answers at once, empty
    }
  }

  // ---- LIFELINES (hier) ----
  // Rank r, dry after a round, registers at each of its lifelines (a put each, issued one after another); it then
  // reads the global count (kRoundStart) and waits. Returns when its puts are complete.
  double register_hungry(double t, int r) {
    Rank& k = at(r);
    k.directed = -1;
    k.registered = true;
    for (std::size_t i = 0; i < k.lifelines.size(); ++i) {
      at(k.lifelines[i]).hungry_in[i] = 1;  // seen from its arrival (t + put / 2): optimistic by that
      t = op(t, k.lifelines[i], lat_.put, false);
    }
    return t;
  }
  // Rank r's worker 0, at an item boundary with items to spare: invites every rank registered here (a put each),
  // returning when its puts are complete. A rank no longer registered (it found work) ignores its invitation.
  double invite_hungry(double t, int r) {
    Rank& k = at(r);
    for (std::size_t i = 0; i < k.hungry_in.size(); ++i) {
      if (!k.hungry_in[i]) continue;
      k.hungry_in[i] = 0;
      const int h = (r - (1 << i) % p_ + p_) % p_;
      const double arrives = t + lat_.put / 2;
      t = op(t, h, lat_.put, false);
      Rank& hungry = at(h);
      if (!hungry.registered || hungry.frame_over) continue;  // it found work meanwhile
      hungry.registered = false;
      hungry.directed = r;  // a rank still on its way to waiting finds the invitation when it gets there
      if (!hungry.waiting) continue;
      hungry.waiting = false;
      hungry.round_tried = 0;
      hungry.step = Step::kTryVictim;
      wake(arrives + kLocalPollNs, h * threads_);
    }
    return t;
  }
  // Rank `detector` read the count at 0 at t (lifelines.hpp, L2): it tells rank 0 (unless it is rank 0) and its
  // children in the binomial tree rooted at rank 0 (rank i's children: i + 2^j for every 2^j > i), one put after
  // another; every rank forwards to its own children when the notice reaches it.
  void tell_frame_over(double t, int detector) {
    std::vector<double> learned(static_cast<std::size_t>(p_), kNever);
    using Arrival = std::pair<double, int>;
    std::priority_queue<Arrival, std::vector<Arrival>, std::greater<>> pending;
    learned[static_cast<std::size_t>(detector)] = t;
    pending.push({t, detector});
    while (!pending.empty()) {
      const auto [when, u] = pending.top();
      pending.pop();
      if (when > learned[static_cast<std::size_t>(u)]) continue;
      std::vector<int> to;
      if (u == detector && u != 0) to.push_back(0);
      int step = 1;
      while (step <= u) step *= 2;
      for (; u + step < p_; step *= 2) to.push_back(u + step);
      double sent = when;
      for (int v : to) {
        const double arrives = sent + lat_.put / 2 + kLocalPollNs;
        sent += lat_.put;
        if (arrives < learned[static_cast<std::size_t>(v)]) {
          learned[static_cast<std::size_t>(v)] = arrives;
          pending.push({arrives, v});
        }
      }
    }
    for (int r = 0; r < p_; ++r) {
      if (r == detector) continue;
      Rank& k = at(r);
      const double when = learned[static_cast<std::size_t>(r)];
      if (k.frame_over || when >= k.notice_at) continue;
      k.notice_at = when;
      for (int t2 = 0; t2 < threads_; ++t2) {
        Worker& y = worker(r * threads_ + t2);
        const bool waiting = t2 == 0 ? k.waiting : y.pending == kIdle;
        if (!y.done && waiting && (t2 == 0 || y.next_at > when)) wake(when, r * threads_ + t2);
      }
    }
  }

  void audit(Result& res) {
    if (hier(s_) && res.exactly_once) {  // termination: every worker learned the frame was over
      for (std::size_t id = 0; id < workers_.size(); ++id) {
        if (workers_[id].done) continue;
        res.exactly_once = false;
        res.audit_failure = "frame " + std::to_string(frame_) + ": rank " + std::to_string(id / threads_) +
                            " (worker " + std::to_string(id % threads_) + ") never learned the frame was over";
        return;
      }
    }
    if (s_ == Scheduler::kHier) {  // which rank ran each item: the costs it knows next frame
      last_runner_.resize(w_.items);
      for (int r = 0; r < p_; ++r) {
        for (ItemId id : at(r).executed) last_runner_[id] = r;
      }
    }
    audit_.clear();
    for (const Rank& k : ranks_) audit_.count(k.executed);
    if (const auto failure = audit_.first_failure(); failure && res.exactly_once) {
      res.exactly_once = false;
      res.audit_failure = "frame " + std::to_string(frame_) + ": " + failure->what();
    }
  }

  Scheduler s_;
  int p_;
  Workload w_;
  Latencies lat_;
  Defect defect_;
  SyntheticCost cost_;
  int threads_;
  std::vector<Worker> workers_;   // hier: rank r's worker t is workers_[r * threads_ + t]
  std::vector<int> last_runner_;  // hier: the rank that ran each item in the last frame
  std::vector<float> predicted_;  // hier-seeded: this frame's predicted item costs (cost_seeded_lists.hpp)
  std::vector<Rank> ranks_;
  std::vector<std::vector<ItemId>> space_blocks_;  // static-space: each rank's contiguous block
  int frame_ = 0;
  std::int64_t active_ = 0;
  std::uint64_t next_item_ = 0, steals_ = 0, attempts_ = 0, remote_ops_ = 0, local_steals_ = 0;
  double steal_ns_ = 0;
  using Events = simulation::EventQueue<int>;
  Events events_{simulation::Ties::kInArrivalOrder};
  simulation::ExactlyOnceAudit audit_;
};

}  // namespace

Result simulate(Scheduler s, int ranks, const Workload& w, const Latencies& lat, std::uint64_t seed, Defect defect) {
  const bool flat = s == Scheduler::kRma || s == Scheduler::kRequest || s == Scheduler::kCentral;
  if (flat && w.threads > 1) {  // one rank per worker (MPI everywhere): ranks x threads ranks of one thread
    Workload one = w;
    one.threads = 1;
    Result r = Model(s, ranks * w.threads, one, lat, seed, defect).run();
    r.ranks = ranks;
    r.threads = w.threads;
    return r;
  }
  return Model(s, ranks, w, lat, seed, defect).run();
}

WorkloadLimits workload_limits(const std::vector<std::vector<double>>& frame_costs, int workers) {
  WorkloadLimits limits;
  limits.workers = workers;
  double work = 0, bound_ns = 0, greedy_ns = 0, lpt_ns = 0;
  // The makespan of `order` given to the first free worker (a min-heap of the workers' free times).
  const auto list_schedule = [workers](const std::vector<double>& order) {
    std::vector<double> free_at(static_cast<std::size_t>(workers), 0.0);
    for (double c : order) {
      std::pop_heap(free_at.begin(), free_at.end(), std::greater<>());
      free_at.back() += c;
      std::push_heap(free_at.begin(), free_at.end(), std::greater<>());
    }
    return *std::max_element(free_at.begin(), free_at.end());
  };
  for (const std::vector<double>& items : frame_costs) {
    double frame_work = 0, largest = 0;
    for (double c : items) {
      frame_work += c;
      largest = std::max(largest, c);
    }
    work += frame_work;
    limits.max_item_ns = std::max(limits.max_item_ns, largest);
    bound_ns += std::max(frame_work / workers, largest);
    greedy_ns += list_schedule(items);
    std::vector<double> longest_first = items;
    std::sort(longest_first.begin(), longest_first.end(), std::greater<>());
    lpt_ns += list_schedule(longest_first);
  }
  if (work > 0) {
    limits.bound = work / (workers * bound_ns);
    limits.greedy = work / (workers * greedy_ns);
    limits.lpt = work / (workers * lpt_ns);
  }
  return limits;
}

WorkloadLimits workload_limits(const Workload& w, int workers) {
  const SyntheticCost cost(w.shape, w.items, w.frames, w.skew);
  std::vector<std::vector<double>> frames(static_cast<std::size_t>(w.frames), std::vector<double>(w.items));
  for (int f = 0; f < w.frames; ++f) {
    for (ItemId id = 0; id < w.items; ++id) frames[static_cast<std::size_t>(f)][id] = cost.units(f, id) * w.light_ns;
  }
  return workload_limits(frames, workers);
}

std::pair<const char*, double> LossAccount::bottleneck() const {
  std::pair<const char*, double> worst{"none", 0.0};
  for (const auto& [name, ns] : {std::pair<const char*, double>{"claims", claims},
                                 {"local steals", local_steals},
                                 {"remote steals", remote_steals},
                                 {"idle (back-off)", idle},
                                 {"tail (finished early)", tail},
                                 {"frame-end barrier", barrier}}) {
    if (ns > worst.second) worst = {name, ns};
  }
  const double all = total();
  return {worst.first, all > 0 ? worst.second / all : 0.0};
}

}  // namespace frontsteal::mpi::sim
