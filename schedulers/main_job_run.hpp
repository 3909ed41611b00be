// main_job_run.hpp — the main job's measurement: every scheduler at every P (a Cell each) set up with one
// untimed warm-up frame, then interleaved rounds — repeat r of the serial loop and of every cell before repeat
// r+1 of any — so slow drifts of a noisy machine spread over all of them; the --interference co-runner
// around them; the noise monitor's samples before, during and after.
//
// Roles: the main thread runs the serial loop (T1) and drives the schedulers; each cell's scheduler (or, for
// openmp-static-steal, its child process) runs the frames. Every frame goes through account_frame
// (main_job_cell.hpp): the same totals and audits whichever way it ran.
// Reaping: the co-runner and the children belong to this object; its destructor stops and reaps them on
// every way out of main (PR_SET_PDEATHSIG covers std::exit and being killed).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/thread_pinning.hpp"
#include "schedulers/interference.hpp"
#include "schedulers/main_job_cell.hpp"
#include "schedulers/main_job_options.hpp"
#include "schedulers/main_job_progress.hpp"
#include "schedulers/main_job_workload.hpp"
#include "schedulers/noise_monitor.hpp"
#include "schedulers/pass_usage.hpp"

namespace frontsteal::main_job {

// The progress steps of a run: the warm-up, then per repeat the serial loop and every scheduler at every P.
std::size_t progress_steps(const Options& o);

class Measurement {
 public:
  // One cell per P in o.threads and scheduler in o.schedulers, nothing started yet.
  Measurement(Options& o, Workload& wl, FrameTessellator& tess);

  // Constructs every cell's scheduler (static partitions computed here, timed) and runs one untimed warm-up
  // frame; openmp-static-steal starts its child per P (it warms up itself). Cells that cannot start are moved
  // to not_available() and reported, not measured. False (after a message) when an in-process scheduler
  // cannot start.
  bool start_cells(const sc::WorkloadHints& hints);
  // --interference: starts the co-runner (after the warm-ups). False (after a message) when it cannot start.
  bool start_interference();
  // The interleaved rounds. Under --repeats auto (`auto_repeats`) whole rounds stop once o.budget_s is spent
  // (never fewer than 5), noted in `repeats_note`. False (after a message) when a scheduler fails.
  bool run_rounds(Progress& progress, bool auto_repeats, std::string& repeats_note);
  // The noise monitor's "after" window: a short pause with nothing of ours running; then the co-runner is
  // killed and reaped, so nothing of ours runs while the results are written.
  void finish();

  const std::vector<double>& serial_path_ms() const { return serial_path_ms_; }
  const std::vector<std::vector<double>>& serial_frame_ms() const { return serial_frame_ms_; }
  const std::vector<nz::Usage>& serial_usage() const { return serial_usage_; }
  const std::vector<double>& serial_probe() const { return serial_probe_; }
  const std::vector<nz::PassUsage>& serial_pass_usage() const { return serial_pass_usage_; }
  const std::vector<Cell>& cells() const { return cells_; }
  const std::vector<Cell>& not_available() const { return not_available_; }
  const nz::ProcSample& measure_start() const { return measure_start_; }
  const nz::ProcSample& measure_end() const { return measure_end_; }
  const nz::ProcSample& at_end() const { return at_end_; }
  int co_runner_cpu() const;  // -1: not pinned (or no co-runner)

 private:
  nz::ProcSample sample() const { return nz::sample_now(co_runner_.pid()); }
  void pin_as(WorkerId w) const;
  void unpin_caller() const;
  bool start_child(Cell& c);
  void run_serial_path();
  void run_cell_path(Cell& c);
  void run_child_path(Cell& c);

  Options& o_;
  Workload& wl_;
  FrameTessellator& tess_;
  const ThreadPinning pinning_;
  fi::CoRunner co_runner_;
  ExecutionCounter runs_;
  std::vector<Cell> cells_, not_available_;
  std::vector<double> serial_path_ms_;
  std::vector<std::vector<double>> serial_frame_ms_;
  std::vector<nz::Usage> serial_usage_;  // per repeat: the machine while the serial loop ran
  std::vector<double> serial_probe_;     // per repeat: the CPU speed probe around the serial loop (cpu_speed_probe.hpp)
  std::vector<nz::PassUsage> serial_pass_usage_;  // per repeat: what the serial loop's thread did (pass_usage.hpp)
  nz::ProcSample measure_start_, measure_end_, at_end_;
};

}  // namespace frontsteal::main_job
