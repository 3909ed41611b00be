// loss_account.hpp — where the time of a frame went, per scheduler and P: the frame's P × T (T by the harness's
// clock) split into what every worker did, made exact for one frame (Olivier, de Supinski, Schulz & Prins,
// "Characterizing and Mitigating Work Time Inflation in Task Parallel Programs", SC'12: idleness, scheduling
// overhead, work time inflation; Tallent & Mellor-Crummey, PPoPP'09: idleness and overhead blame).
//
// The terms, each a share of P × T (they add up to 1):
//   work         the items' own work (the item function less the harness's checks)
//   claim        the scheduler's per-item claim within its claims (the owner path of a drain; a chunk's loop),
//                and for schedulers whose phases are not timed, all the time between their claims
//   checks       the harness's per-item checks (exactly-once count, pinning): the main job's, not the scheduler's
//   wake         release of the frame → the worker's first claim
//   search       looking for work that was then found (victims examined, lock busy, empty lists, polls; a global
//                queue's lock waits)
//   steal        successful steals: victim's LockList held → share installed (T1–T5, the share's copy, install)
//   wait         waiting at T4 for a victim's ListTransient to fall
//   termination  the end of the worker's last items → the caller sees the frame done (the last, failed search,
//                the arrival, the last arriver's installs, the caller's wake-up)
//   off-cpu      active − cpu: time the worker's thread had no CPU, taken out of the terms above (but wake) in
//                proportion to their size (where in its span it fell is not measured: the thread CPU clock is a
//                system call, read once per worker and frame)
//   unaccounted  P × T less every term measured: the harness's own time around the scheduler's window and any
//                time no phase claims (a test plants a spin there: the account must then not close)
// Work, claim and checks split the measured busy time: checks and the per-item claim are the harness's sampled
// item timings (measure/item_sampler.hpp) times the items; work is the rest. Work is then compared with the
// serial loop's work on the same sampled surfaces in the same rounds (work inflation), and with the limit arm's
// (limit_arm.hpp): inflation the machine imposes on P busy cores against inflation the scheduler adds.
//
// The account CLOSES when |unaccounted| ≤ kClosureBound of P × T, over the run and frame by frame.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/frame_stats.hpp"
#include "measure/item_sampler.hpp"

namespace frontsteal::main_job {

inline constexpr double kClosureBound = 0.02;

enum class Term { kWork, kClaim, kChecks, kWake, kSearch, kSteal, kWait, kTermination, kOffCpu, kUnaccounted };
inline constexpr std::size_t kTerms = 10;
const char* name(Term t) noexcept;      // "work", "claim", ... (the JSON keys and column names)
const char* describe(Term t) noexcept;  // "idle at the frame's end" and the like (the answer's words)

// What a cell's frames add up to, for its account: sums over every measured frame and worker (ns).
struct AccountSums {
  double available_ns = 0;  // Σ P × T, T the harness's frame time (a calibration arm's planted work left out)
  double window_ns = 0;     // Σ P × the scheduler's own window (FrameStats::wall_ns)
  double wake_ns = 0, busy_ns = 0, search_ns = 0, steal_ns = 0, wait_ns = 0, termination_ns = 0;
  double between_ns = 0;  // schedulers without timed phases: all the time between their claims
  double active_ns = 0, cpu_ns = 0, off_cpu_ns = 0;
  double items = 0, claims = 0;
  bool phases_timed = false;                  // the scheduler timed search, steal and wait (FrameStats)
  std::uint64_t frames = 0, frames_open = 0;  // frames, and those whose own account did not close
  double worst_frame_open = 0;                // the largest |unaccounted| / (P T) of one frame
  measure::ItemSamples samples;

  // One frame: the scheduler's statistics, the harness's frame time, and the samples the frame's items left.
  void add_frame(const FrameStats& stats, double harness_ns, measure::ItemSamples frame_samples);
};

// The account of one cell: every term in ns (summed over frames and workers) and as a share of P × T.
struct LossAccount {
  std::array<double, kTerms> ns{};
  double available_ns = 0;
  double checks_per_item_ns = 0, claim_per_item_ns = 0;  // the sampled timings the split used
  std::uint64_t samples = 0, gaps = 0;
  bool phases_timed = false;  // search, steal and wait measured (the stealing protocol); else one claim term
  double share(Term t) const { return available_ns > 0 ? ns[static_cast<std::size_t>(t)] / available_ns : 0; }
  bool closes() const {
    return share(Term::kUnaccounted) <= kClosureBound && share(Term::kUnaccounted) >= -kClosureBound;
  }
};

LossAccount make_account(const AccountSums& sums);

}  // namespace frontsteal::main_job
