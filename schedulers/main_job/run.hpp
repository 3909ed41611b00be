// run.hpp — the main job's measurement: every arm (the serial loop, every scheduler at every P, and
// under --calibrate the calibration arms) set up with one untimed warm-up frame, then ROUNDS: a round covers one
// segment of the path (--round-frames frames) at one P and runs the serial loop and every arm at that P once on
// it, in the order measure/round_order.hpp gives for that round (random by default). A pass is one round per
// segment and P; --repeats counts passes. Every --instance-frames frames of a pass every arm is built afresh at
// a random heap offset and warmed up untimed on the frame before (openmp-static-steal's child: once a pass), and
// each round records which instance ran it: two instances of the same code differ for as long as they live,
// and the analysis needs the instances as clusters to include that. Every frame
// is timed by this object's clock around the scheduler's run_frame (and the planted work of a calibration arm),
// the scheduler's own wall_ns kept as a cross-check; the CPU speed probe is timed on this thread just before each
// arm runs (the covariate of measure/paired_analysis.hpp). The --interference co-runner runs around them; the
// noise monitor samples before, during and after.
//
// Roles: the main thread runs the serial loop (T1) and drives the schedulers; each cell's scheduler (or, for
// openmp-static-steal, its child process) runs the frames. Every frame goes through account_frame
// (cell.hpp): the same totals and audits whichever way it ran.
// Reaping: the co-runner and the children belong to this object; its destructor stops and reaps them on
// every way out of main (PR_SET_PDEATHSIG covers std::exit and being killed).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/execution_log.hpp"
#include "measure/thread_pinning.hpp"
#include "measure/interference.hpp"
#include "measure/item_sampler.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/pass_usage.hpp"
#include "schedulers/main_job/cell.hpp"
#include "schedulers/main_job/options.hpp"
#include "schedulers/main_job/progress.hpp"
#include "schedulers/main_job/workload.hpp"

namespace frontsteal::main_job {

// Segments of the path: ceil(frames / round_frames). A pass is one round per segment and P.
int segments(const Options& o);
// The distinct worker counts of the run (the P of its rounds).
int distinct_p(const Options& o);
// The progress steps of a run: the warm-up, then every round.
std::size_t progress_steps(const Options& o);

// --repeats auto: the pilot's passes, and the fewest passes a run makes.
inline constexpr int kPilotPasses = 3;
inline constexpr int kMinPasses = 5;

class Measurement {
 public:
  // One cell per P in o.threads and scheduler in o.schedulers (and the calibration arms), nothing started yet.
  // `warm` gives the serial frame times the planted work is sized from.
  // `limit`: the limit arms' copies (nullptr: no limit arm).
  Measurement(Options& o, Workload& wl, FrameTessellator& tess, const WarmUp& warm, LimitCopies* limit);

  // Constructs every cell's scheduler (static partitions computed here, timed; the first instance of each
  // cell; run_rounds builds fresh ones every o.instance_frames frames) and runs one untimed warm-up frame;
  // openmp-static-steal starts its child per P (it warms up itself). Cells that cannot start are moved to
  // not_available() and reported, not measured. False (after a message) when an in-process scheduler cannot start.
  bool start_cells(const sc::WorkloadHints& hints);
  // --interference: starts the co-runner (after the warm-ups). False (after a message) when it cannot start.
  bool start_interference();
  // The rounds, pass by pass. Under --repeats auto (`auto_repeats`) a pilot of kPilotPasses passes sizes the
  // run from the spread of the paired log-ratios (measure::rounds_for_power at the margin), within o.budget_s,
  // and whole passes stop once the budget is spent (never fewer than kMinPasses); noted in `repeats_note`.
  // False (after a message) when a scheduler fails.
  bool run_rounds(Progress& progress, bool auto_repeats, std::string& repeats_note);
  // The noise monitor's "after" window: a short pause with nothing of ours running; then the co-runner is
  // killed and reaped, so nothing of ours runs while the results are written.
  void finish();

  const std::vector<double>& serial_path_ms() const { return serial_path_ms_; }
  const std::vector<std::vector<double>>& serial_frame_ms() const { return serial_frame_ms_; }
  const std::vector<nz::Usage>& serial_usage() const { return serial_usage_; }
  const std::vector<double>& serial_probe() const { return serial_probe_; }
  const std::vector<nz::PassUsage>& serial_pass_usage() const { return serial_pass_usage_; }
  const measure::ArmRounds& serial_rounds() const { return serial_rounds_; }
  // Per round as serial_rounds(): the serial loop's work on the sampled surfaces (ms).
  const measure::ArmRounds& serial_sampled() const { return serial_sampled_; }
  // The harness's item sampler (how many surfaces it times, what one clock read costs).
  const measure::ItemSampler& sampler() const { return sampler_; }
  const std::vector<Cell>& cells() const { return cells_; }
  const std::vector<Cell>& not_available() const { return not_available_; }
  const nz::ProcSample& measure_start() const { return measure_start_; }
  const nz::ProcSample& measure_end() const { return measure_end_; }
  const nz::ProcSample& at_end() const { return at_end_; }
  int co_runner_cpu() const;  // -1: not pinned (or no co-runner)

 private:
  // The machine now; the CPU time of the children restarted meanwhile (gone from /proc) counted as ours.
  nz::ProcSample sample() const {
    nz::ProcSample s = nz::sample_now(co_runner_.pid());
    s.children_ticks += retired_child_ticks_;
    return s;
  }
  void pin_as(WorkerId w) const;
  void unpin_caller() const;
  bool start_child(Cell& c);
  void add_calibration_arms(const WarmUp& warm);
  void resize_planted_work();
  void run_round(std::size_t round, WorkerId p, int segment);
  void run_serial_segment(std::size_t round, int segment, double probe);
  void run_cell_segment(Cell& c, std::size_t round, int segment, double probe);
  void run_child_segment(Cell& c, std::size_t round, int segment, double probe);
  void run_limit_segment(Cell& c, std::size_t round, int segment, double probe);
  void add_limit_arms();
  void begin_pass();
  void renew_instances(int pass, int first_frame);
  int instance_of(const Cell& c) const;
  std::unique_ptr<sc::Scheduler> make_instance(Cell& c, std::uint64_t draw);
  int passes_from_pilot(double pass_s, std::string& note) const;

  Options& o_;
  Workload& wl_;
  FrameTessellator& tess_;
  LimitCopies* limit_copies_;
  const ThreadPinning pinning_;
  fi::CoRunner co_runner_;
  ExecutionLog runs_;  // the exactly-once audit: a plain log per worker (core/execution_log.hpp says why)
  measure::ItemSampler sampler_;
  std::vector<Cell> cells_, not_available_;
  std::vector<double> serial_path_ms_;                // per pass
  std::vector<std::vector<double>> serial_frame_ms_;  // [pass][frame]
  std::vector<nz::Usage> serial_usage_;               // per pass: the machine while the serial loop ran
  std::vector<double> serial_probe_;                  // per pass: the smallest CPU speed probe before its segments
  std::vector<nz::PassUsage> serial_pass_usage_;      // per pass: what the serial loop's thread did (pass_usage.hpp)
  measure::ArmRounds serial_rounds_;                  // per round: the serial loop's segment time, probe, segment
  measure::ArmRounds serial_sampled_;                 // per round: the serial loop's sampled work (ms)
  double pass_probe_min_ = 0;                         // the smallest probe before the serial loop's segments this pass
  std::vector<WorkerId> ps_;                          // the P of the rounds: every P some cell runs at
  std::size_t rounds_done_ = 0;
  sc::WorkloadHints hints_;                    // kept for the instances built after the first
  std::uint64_t instances_built_ = 1'000'000;  // draws of the heap offsets after start_cells' own
  std::uint64_t retired_child_ticks_ = 0;      // CPU ticks of the children replaced by fresh ones
  nz::ProcSample measure_start_, measure_end_, at_end_;
};

}  // namespace frontsteal::main_job
