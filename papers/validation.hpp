// validation.hpp — does the simulator agree with measurement? Predictions of the main job's path times
// (schedulers/main_job/frontsteal_main.cpp, results in frontsteal.json) from cost traces, against what it measured.
//
// Held out: the model's constants come from microbenchmarks (calibration.hpp) and from ONE measured set, the
// calibration set (a path without interference); every other set is predicted without refitting anything.
// The one constant taken from the calibration set is `trace_scale`: the main job's serial loop time there over
// the trace's Σ costs of the same path (the trace is recorded on another day, on a machine in another state).
// Interference is an input, not a fit: the co-runner's measured core share s (frontsteal.json) makes the worker
// that shares its core (worker 0, pinned) 1 / (1 − s) slower.
//
// Error of a cell: 100 × (predicted − measured) / measured, path times (median of the repeats).
//
// Ratios, which survive a machine whose speed changes (main-job JSON schema 3): per cell the paired ratio of its
// time to the serial loop's and to queue-mutex's at the same P, with the 95 % interval the main job measured;
// predicted as the ratio of two simulated times. The trace scale cancels in a ratio, so every set is held out.
// Two errors per ratio: against the point estimate, and against the interval (0 inside it, else the distance to
// the nearer bound, relative to that bound).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "papers/calibration.hpp"
#include "papers/cost_trace.hpp"
#include "papers/simulator.hpp"

namespace frontsteal::papers {

// A paired ratio the main job measured, with its 95 % interval (valid: the file had one).
struct MeasuredRatio {
  double ratio = 0, low = 0, high = 0;
  bool valid = false;
};

// The loss account the main job measured for one row (frontsteal.json schema 4, schedulers/main_job/
// loss_account.hpp): every term's share of P x T, the sampled per-item timings, the work's inflation against the
// serial loop, and per worker the wake-up and termination summed over the frames.
struct MeasuredAccount {
  std::map<std::string, double> shares;  // work, claim, checks, wake, search, steal, wait, termination, off_cpu, ...
  double claim_per_item_ns = 0, checks_per_item_ns = 0;
  double inflation = 1;  // the sampled work against the serial loop's (1 when not measured)
  std::uint64_t frames = 0;
  std::vector<double> wake_ms, termination_ms;  // per worker, summed over the frames
  // The shares before off-CPU time was taken out of the in-span terms (the simulator has no off-CPU time):
  // each in-span term t as t x (span + off) / span.
  std::map<std::string, double> shares_with_off_cpu() const;
};

// One scheduler at one P of a main-job run.
struct MeasuredCell {
  std::string scheduler;
  WorkerId workers = 0;
  double path_ms = 0;                      // median of the repeats
  double spread_pct = 0;                   // the repeats' spread (max/min − 1), as the main job reports it
  MeasuredRatio vs_serial, vs_queue;       // T_P / T1 and T_P / T_queue-mutex, paired by round (schema 3)
  std::optional<MeasuredAccount> account;  // schema 4
};

// One frontsteal.json: a path, with or without interference.
struct MeasuredSet {
  std::string name;  // the directory it came from, e.g. walkthrough-pinned
  std::string path, scene;
  std::string machine;  // where the main job measured it
  bool interference = false;
  double co_runner_share = 0;  // of one core, measured while the schedulers ran (0 without interference)
  double serial_ms = 0;        // the serial loop's median path time (co-runner paused)
  std::vector<MeasuredCell> cells;
  std::map<WorkerId, std::vector<double>> limit_copy_time;  // schema 4: per P, the limit arm's copy_relative_time
};

// Reads the fields above from a main-job JSON (schema 2, docs/results-schema.md); throws std::runtime_error
// naming the file and the missing key.
MeasuredSet read_measured_set(const std::filesystem::path& json_file, const std::string& name);

// Every measured set of a study folder: each subfolder holding a frontsteal.json, named by the subfolder, sorted
// by name.
std::vector<MeasuredSet> read_study(const std::filesystem::path& study);

// The simulator's model of a registry scheduler; nullopt when it has none.
std::optional<Model> model_of(const std::string& scheduler);

// Worker slowdowns of a set at P workers: worker 0 shares its core with the co-runner.
std::vector<double> slowdown_of(const MeasuredSet& set, WorkerId workers);

// The predicted path time (ms) of `scheduler` at `workers` on `trace` scaled by `trace_scale`.
double predict_path_ms(const CostTrace& trace, double trace_scale, const Overheads& overheads,
                       const std::string& scheduler, WorkerId workers, const std::vector<double>& slowdown,
                       std::uint64_t seed);

double error_pct(double predicted, double measured);  // throws std::invalid_argument when measured ≤ 0
// 0 when `predicted` lies inside the measured interval, else its error against the nearer bound.
double interval_error_pct(double predicted, const MeasuredRatio& measured);

struct ErrorSummary {
  std::size_t cells = 0;
  double median_abs_pct = 0, worst_abs_pct = 0, mean_signed_pct = 0;
  std::size_t worst_index = 0;  // into the errors given
};
ErrorSummary summarize_errors(const std::vector<double>& errors_pct);  // throws on an empty list

// The validation goal: median |error| <= 5 %, worst <= 10 %.
inline bool meets_goal(const ErrorSummary& s) { return s.median_abs_pct <= 5.0 && s.worst_abs_pct <= 10.0; }

// The model without the terms added for validation (affinity, lock wake-up, wake-up skew) and without
// interference: the baseline the validation table compares against.
Overheads without_new_terms(Overheads o);

}  // namespace frontsteal::papers
