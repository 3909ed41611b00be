// calibration.hpp — the costs the simulator charges on top of the items, measured by microbenchmarks here.
//
//   per model (ModelCosts)   item_ns: a scheduler's time per no-op item at P = 1 (claiming, the indirect call,
//                            the clock reads of busy time), the real scheduler of the registry;
//                            frame_fixed_ns: a frame's cost at P = 1 beyond its items (wake the worker, join:
//                            frames of ~1 ms, so the caller sleeps in the kernel as on real frames);
//                            second_worker_ns: what P = 2 adds (median of interleaved measurements, ≥ 0).
//   extra_worker_ns          each worker beyond 2 (ASSUMED, not measurable here): 1 µs of kernel wake work in
//                            the notify_all plus two line transfers (its arrival RMW and its start read).
//   line_transfer_ns         one cache line moved between two cores: an atomic ping-pong, half a round trip.
//   lock_uncontended_ns      std::mutex lock + cursor update + unlock on one core.
//   lock_handoff_ns          the same under contention from another core: time per acquisition while two
//                            threads hammer one lock (futex sleep and wake included).
//   fence_ns                 one std::atomic_thread_fence(seq_cst) (MFENCE or a locked instruction on x86).
//   lock_wake_ns             a waiter that found the lock held sleeps in the futex: from the holder's unlock
//                            to the waiter running with the lock (median of hand-offs to a sleeping thread).
//   wake_skew_ns             the per-frame wake-up: worker w (w ≥ 1) starts its frame w × this later than worker
//                            0 (notify_all wakes the sleepers one after another; median over frames).
//   affinity_penalty         cache affinity: an item run by another worker than in the previous frame costs
//                            (1 + this) × its traced cost. Measured on the real workload, not by calibrate():
//                            measure_affinity runs one path at P = 2 with each worker's list kept vs shuffled
//                            every frame (paired, interleaved; thread CPU time, so preemption does not count).
// The three default to 0 (term off): a calibration file written before they existed replays as it did.
// Derived (counted from the protocol's accesses to the victim's lines, not measured as a whole):
//   steal = 4 line transfers (LockList CAS, Front/End read, End store, ListTransient + Front re-read) + fence;
//   a busy LockList or a lost Chase–Lev CAS = 1 transfer; an empty victim = 2; Chase–Lev steal = 4 transfers.
// On a machine with one hardware thread the two-thread values cannot be measured: they are then the
// defaults below and `assumed` says so.
#pragma once

#include <filesystem>
#include <functional>
#include <cstdint>
#include <string>
#include <vector>

namespace frontsteal::papers {

struct ModelCosts {
  double item_ns = 5;
  double frame_fixed_ns = 50000;
  double second_worker_ns = 0;
};

struct Overheads {
  ModelCosts static_list, queue, stealing, chase_lev;
  double line_transfer_ns = 80;
  double lock_uncontended_ns = 20;
  double lock_handoff_ns = 150;
  double fence_ns = 20;
  double idle_round_ns = 200;
  double lock_wake_ns = 0;
  double wake_skew_ns = 0;
  double affinity_penalty = 0;     // fraction of the item's cost
  bool affinity_measured = false;  // false: affinity_penalty is not a measurement of this machine
  // The loss account's constants (papers/validation.hpp, account_constants: taken from a measured account), for
  // predicting the account's terms; empty / 0 by default, so a calibration file written before they existed
  // replays as it did. With wake_by_worker_ns set, worker w starts its frame wake_by_worker_ns[min(w, last)]
  // after the release (a further worker is woken on an idle core of its own, in parallel with the others, and
  // costs the kernel's wake of one more thread: extra_worker_ns() more per further worker, ASSUMED), and a frame
  // ends join_ns after the last worker's last item, instead of frame_ns's fixed costs.
  double checks_ns = 0;                   // per item: the harness's per-item checks
  std::vector<double> wake_by_worker_ns;  // per worker index: release → first claim
  double join_ns = 0;                     // the last worker's last item → the caller sees the frame done
  bool account_model() const { return !wake_by_worker_ns.empty(); }
  double wake_of(unsigned w) const {
    if (wake_by_worker_ns.empty()) return w * wake_skew_ns;
    const std::size_t last = wake_by_worker_ns.size() - 1;
    return w <= last ? wake_by_worker_ns[w] : wake_by_worker_ns[last] + (w - last) * extra_worker_ns();
  }
  double extra_worker_ns() const { return 1000 + 2 * line_transfer_ns; }
  double frame_ns(const ModelCosts& m, unsigned workers) const {
    return m.frame_fixed_ns + (workers >= 2 ? m.second_worker_ns : 0) +
           (workers > 2 ? (workers - 2) * extra_worker_ns() : 0);
  }  // a thief's pause after a round without a share (the protocol's spin back-off)
  std::string machine, commit;
  bool assumed = true;  // true: defaults, not measured

  double steal_ns() const { return 4 * line_transfer_ns + fence_ns; }
  double steal_busy_ns() const { return line_transfer_ns; }
  double steal_empty_ns() const { return 2 * line_transfer_ns; }
  double steal_chase_lev_ns() const { return 4 * line_transfer_ns; }
};

// Runs the microbenchmarks (about 5 s). `progress` gets a line per step (may be empty).
Overheads calibrate(const std::string& machine, const std::string& commit,
                    const std::function<void(const std::string&)>& progress);

// The affinity measurement (see affinity_penalty above). Paired: repeat r runs the path with kept lists and
// with shuffled lists back to back (which one first alternates); the penalty is the median over repeats of
// (busy_shuffled − busy_kept) / (traced cost of the items that changed worker), busy in thread CPU time.
struct AffinityMeasurement {
  std::vector<double> kept_busy_ms, shuffled_busy_ms;  // per repeat: Σ over workers of CPU time in items
  std::vector<double> penalty_per_repeat;              // fraction, per repeat
  double moved_fraction = 0;                           // of item runs, shuffled lists (kept: 0 after frame 0)
  double moved_cost_ms = 0;                            // per path: serial cost of the item runs that moved
  double penalty = 0;                                  // median of penalty_per_repeat
  double penalty_ns_per_moved_item = 0;                // the same in ns per moved item
};
class PathWorkload;
AffinityMeasurement measure_affinity(PathWorkload& workload, int repeats, std::uint64_t seed,
                                     const std::function<void(const std::string&)>& progress);

void write_overheads(const Overheads& o, const std::filesystem::path& file);
Overheads read_overheads(const std::filesystem::path& file);  // throws std::runtime_error naming the line
std::string describe(const Overheads& o);                     // a markdown table

}  // namespace frontsteal::papers
