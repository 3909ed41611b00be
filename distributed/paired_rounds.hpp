// paired_rounds.hpp — frontsteal-mpi's comparisons decided by the paired method of measure/paired_analysis.hpp,
// with the method tested in the same run.
//
// DESIGN. One round runs every arm once, for --frames frames each, in an order drawn afresh for the round
// (measure/round_order.hpp, seeded by --seed: every rank computes the same order, nothing is sent). An arm's time
// in a round is the sum of its frame times on rank 0's clock (barrier to barrier: the harness's clock, not the
// scheduler's). Just before each arm, rank 0 times the CPU speed probe (measure/cpu_speed_probe.hpp): the
// covariate of the analysis. Each arm is compared with the reference (--reference) round by round: the log-ratio
// of the two times in the same round, Huber's estimate with a t interval, a verdict against --margin-pct.
//
// THE METHOD, TESTED IN THE SAME RUN (the standard: a comparison counts only if it has called an A/A pair
// equivalent and found a planted slowdown of known size):
//   the A/A twin   the reference scheduler under a second name: it must be called equivalent (never faster or
//                  slower); a twin called different says this run's noise defeats the method.
//   the planted    the reference with rank 0 spinning --planted-pct % of the reference's frame time (from a
//                  warm-up pass) after every frame, inside the timed region: it must be found slower, with an
//                  estimate whose interval holds the size it was planted at.
// Every pass of every arm is audited like any other frame (scheduler_run.hpp).
//
// WHAT THE ROUNDS SHARE. Each arm keeps one runner (SchedulerRun) across rounds for its statistics; every pass
// starts from the same lists (block allocation), so every round of an arm runs the same frames. All arms run in
// the same processes and windows: what differs between two arms of a round is the scheduler and the moment.
#pragma once

#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/mpi_workload.hpp"
#include "distributed/rank_stats.hpp"
#include "distributed/rma_window.hpp"
#include "measure/paired_analysis.hpp"

namespace frontsteal::mpi {

enum class ArmRole { kScheduler, kReference, kTwin, kPlanted };

struct PairedArm {
  std::string label;      // as reported: the scheduler's name, "static-space (A/A twin)", "... +10 % planted"
  std::string scheduler;  // what runs
  ArmRole role = ArmRole::kScheduler;
  double planted_s = 0;  // per frame, spun by rank 0 (kPlanted only)
};

// The arms of a run: every --schedulers entry (the reference among them, added when missing), then the twin and
// the planted arm of the reference.
std::vector<PairedArm> paired_arms(const Options& o);

struct PairedRun {
  std::vector<PairedArm> arms;
  std::size_t reference = 0;               // index of the reference arm in `arms`
  std::vector<measure::ArmRounds> rounds;  // rank 0: per arm, each round's time (s) and the probe before it
  std::vector<SchedulerResult> results;    // per arm: every pass's frames, statistics gathered on rank 0
  double warmup_frame_s = 0;               // the reference's median frame time in the warm-up pass (rank 0)
  int rounds_done = 0;
  bool ok = true;  // false: an audit failed (rank 0 printed it); the run stopped there
};

// Runs the warm-up and every round. Collective over MPI_COMM_WORLD; progress on stderr (rank 0).
PairedRun run_paired_rounds(const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                            double owner_progress_us);

// One arm against the reference (rank 0, from PairedRun::rounds).
struct ArmComparison {
  std::string label;
  ArmRole role = ArmRole::kScheduler;
  measure::PairedResult result;  // candidate = the arm, reference = the reference arm; ratio = time ratio
  double planted_pct = 0;        // kPlanted: the planted size as % of the reference's mean round time in the run
};

// What the calibration arms say about this run's method.
struct MethodCheck {
  bool twin_equivalent = false;    // the A/A twin called equivalent
  bool twin_false_alarm = false;   // the A/A twin called faster or slower
  bool planted_found = false;      // the planted arm called slower
  bool planted_size_held = false;  // the planted arm's interval holds the planted size
  bool passed() const { return !twin_false_alarm && planted_found; }
};

std::vector<ArmComparison> compare_arms(const PairedRun& run, double margin_pct);
MethodCheck check_method(const std::vector<ArmComparison>& comparisons);

}  // namespace frontsteal::mpi
