// validation_report.cpp — the files of `frontsteal-paper validate` (validation_report.hpp).
#include "papers/validation_report.hpp"

#include <algorithm>
#include <iostream>
#include <sstream>

#include "measure/machine_info.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"

namespace frontsteal::papers {

void write_validation_report(const ValidationRun& run, const std::string& out, bool quiet) {
  // ---- tables -------------------------------------------------------------------------------------------------
  using report::Cell;
  report::Table cells({{"set", "set", false},
                       {"path", "path", false},
                       {"interference", "interference", false},
                       {"held_out", "held out", false},
                       {"scheduler", "scheduler", false},
                       {"workers", "P"},
                       {"measured_ms", "measured (ms)"},
                       {"spread_pct", "repeats' spread (%)"},
                       {"predicted_ms", "predicted (ms)"},
                       {"error_pct", "error (%)"},
                       {"baseline_ms", "old model (ms)"},
                       {"baseline_error_pct", "old model error (%)"}});
  for (const ValidationRow& r : run.rows) {
    cells.add_row({r.set->name, r.set->path, r.set->interference, r.held_out, r.cell.scheduler, r.cell.workers,
                   Cell::fixed(r.cell.path_ms, 1), Cell::fixed(r.cell.spread_pct, 1), Cell::fixed(r.predicted_ms, 1),
                   Cell::fixed(error_pct(r.predicted_ms, r.cell.path_ms), 1), Cell::fixed(r.baseline_ms, 1),
                   Cell::fixed(error_pct(r.baseline_ms, r.cell.path_ms), 1)});
  }
  report::Table summary({{"cells_of", "cells", false},
                         {"cells", "n"},
                         {"median_abs_error_pct", "median |error| (%)"},
                         {"worst_abs_error_pct", "worst |error| (%)"},
                         {"worst_cell", "worst cell", false},
                         {"mean_signed_error_pct", "mean signed error (%)"},
                         {"goal_met", "goal met (median ≤ 5 %, worst ≤ 10 %)", false},
                         {"baseline_median_abs_error_pct", "old model: median |error| (%)"},
                         {"baseline_worst_abs_error_pct", "old model: worst |error| (%)"}});
  auto summarize_rows = [&](const std::string& label, auto keep) {
    std::vector<double> e, b;
    std::vector<const ValidationRow*> which;
    for (const ValidationRow& r : run.rows) {
      if (!keep(r)) continue;
      e.push_back(error_pct(r.predicted_ms, r.cell.path_ms));
      b.push_back(error_pct(r.baseline_ms, r.cell.path_ms));
      which.push_back(&r);
    }
    if (e.empty()) return;
    const ErrorSummary s = summarize_errors(e), sb = summarize_errors(b);
    const ValidationRow& w = *which[s.worst_index];
    summary.add_row({label, static_cast<std::uint64_t>(s.cells), Cell::fixed(s.median_abs_pct, 1),
                     Cell::fixed(s.worst_abs_pct, 1),
                     w.set->name + " " + w.cell.scheduler + " P=" + std::to_string(w.cell.workers),
                     Cell::fixed(s.mean_signed_pct, 1), meets_goal(s), Cell::fixed(sb.median_abs_pct, 1),
                     Cell::fixed(sb.worst_abs_pct, 1)});
  };
  summarize_rows("calibration set " + run.calibration_set->name, [&](const ValidationRow& r) { return !r.held_out; });
  summarize_rows("all held-out cells", [&](const ValidationRow& r) { return r.held_out; });
  for (const MeasuredSet& s : run.sets) {
    if (s.name == run.calibration_set->name) continue;
    summarize_rows("held out: " + s.name, [&](const ValidationRow& r) { return r.set == &s; });
  }
  for (unsigned p : run.threads) {
    summarize_rows("held out, P = " + std::to_string(p),
                   [&](const ValidationRow& r) { return r.held_out && r.cell.workers == p; });
  }
  for (const char* sched : {"round-robin", "queue-mutex", "stealing/Fenced", "chase-lev"}) {
    summarize_rows(std::string("held out, ") + sched,
                   [&](const ValidationRow& r) { return r.held_out && r.cell.scheduler == sched; });
  }
  // Does the model reproduce the gap that matters: stealing against the queue, at the largest P?
  const unsigned pmax = *std::max_element(run.threads.begin(), run.threads.end());
  report::Table gap({{"set", "set", false},
                     {"workers", "P"},
                     {"measured_gain_pct", "measured: stealing ahead of queue (%)"},
                     {"predicted_gain_pct", "predicted (%)"},
                     {"baseline_gain_pct", "old model (%)"}});
  for (const MeasuredSet& s : run.sets) {
    const ValidationRow *q = nullptr, *st = nullptr;
    for (const ValidationRow& r : run.rows) {
      if (r.set != &s || r.cell.workers != pmax) continue;
      if (r.cell.scheduler == "queue-mutex") q = &r;
      if (r.cell.scheduler == "stealing/Fenced") st = &r;
    }
    if (!q || !st) continue;
    gap.add_row({s.name, pmax, Cell::fixed(100 * (q->cell.path_ms / st->cell.path_ms - 1), 1),
                 Cell::fixed(100 * (q->predicted_ms / st->predicted_ms - 1), 1),
                 Cell::fixed(100 * (q->baseline_ms / st->baseline_ms - 1), 1)});
  }

  // ---- ratios: what survives a machine whose speed changes -----------------------------------------------------
  report::Table ratio_cells({{"set", "set", false},
                             {"scheduler", "scheduler", false},
                             {"workers", "P"},
                             {"kind", "ratio", false},
                             {"measured", "measured [95% CI]", false},
                             {"predicted", "predicted"},
                             {"error_pct", "error (%)"},
                             {"interval_error_pct", "error vs interval (%)"}});
  struct RatioError {
    std::string kind, cell;
    double point = 0, interval = 0;
  };
  std::vector<RatioError> ratio_errors;
  for (const ValidationRow& r : run.rows) {
    auto add = [&](const char* kind, const MeasuredRatio& m, double predicted) {
      if (!m.valid || !(predicted > 0)) return;
      const RatioError e{kind, r.set->name + " " + r.cell.scheduler + " P=" + std::to_string(r.cell.workers),
                         error_pct(predicted, m.ratio), interval_error_pct(predicted, m)};
      ratio_errors.push_back(e);
      ratio_cells.add_row({r.set->name, r.cell.scheduler, r.cell.workers, kind,
                           report::fixed_text(m.ratio, 3) + " [" + report::fixed_text(m.low, 3) + ", " +
                               report::fixed_text(m.high, 3) + "]",
                           Cell::fixed(predicted, 3), Cell::fixed(e.point, 1), Cell::fixed(e.interval, 1)});
    };
    add("T_P / T1", r.cell.vs_serial, r.predicted_vs_serial);
    if (r.cell.scheduler != "queue-mutex") add("T_P / T_queue", r.cell.vs_queue, r.predicted_vs_queue);
  }
  report::Table ratio_summary({{"ratios", "ratios", false},
                               {"n", "n"},
                               {"median_abs_error_pct", "median |error| (%)"},
                               {"worst_abs_error_pct", "worst |error| (%)"},
                               {"median_abs_interval_error_pct", "median |error vs interval| (%)"},
                               {"worst_abs_interval_error_pct", "worst |error vs interval| (%)"},
                               {"inside", "predictions inside the interval", false},
                               {"worst_cell", "worst cell (vs interval)", false},
                               {"goal_met", "goal met vs interval (median ≤ 5 %, worst ≤ 10 %)", false}});
  auto summarize_ratios = [&](const std::string& label, const std::string& kind) {
    std::vector<double> point, interval;
    std::vector<const RatioError*> which;
    std::size_t inside = 0;
    for (const RatioError& e : ratio_errors) {
      if (!kind.empty() && e.kind != kind) continue;
      point.push_back(e.point);
      interval.push_back(e.interval);
      which.push_back(&e);
      if (e.interval == 0) ++inside;
    }
    if (point.empty()) return;
    const ErrorSummary sp = summarize_errors(point), si = summarize_errors(interval);
    ratio_summary.add_row({label, static_cast<std::uint64_t>(sp.cells), Cell::fixed(sp.median_abs_pct, 1),
                           Cell::fixed(sp.worst_abs_pct, 1), Cell::fixed(si.median_abs_pct, 1),
                           Cell::fixed(si.worst_abs_pct, 1),
                           std::to_string(inside) + " of " + std::to_string(point.size()),
                           which[si.worst_index]->cell + " " + which[si.worst_index]->kind, meets_goal(si)});
  };
  summarize_ratios("every ratio", "");
  summarize_ratios("speed-up ratios T_P / T1", "T_P / T1");
  summarize_ratios("against queue-mutex T_P / T_queue", "T_P / T_queue");

  // ---- files ------------------------------------------------------------------------------------------------
  report::ResultsDir dir("frontsteal-paper", out);
  write_overheads(run.constants, dir.file("validation-calibration.txt"));
  std::string other_machines;  // the measured sets' machines that are not this one
  for (const MeasuredSet& s : run.sets) {
    if (s.machine != run.machine && other_machines.find(s.machine) == std::string::npos) {
      other_machines += (other_machines.empty() ? "" : "; ") + s.machine;
    }
  }
  std::ostringstream md;
  md << "# Simulator validation on held-out measurements\n\nMachine: " << run.machine << ". Commit "
     << FRONTSTEAL_GIT_COMMIT << ". Measured sets: the main job's frontsteal.json under the study folder, scene "
     << run.calibration_set->scene << ", path time = median of its repeats. Calibration set: **"
     << run.calibration_set->name << "** — the only measured path times the model sees (the trace scale "
     << report::fixed_text(run.trace_scale, 4)
     << " = its serial loop / the trace's Σ costs). Every other set is held out: predicted with no refit. "
        "Interference enters as the co-runner's measured core share s (worker 0 runs 1/(1 − s) slower). "
        "Traces: median of "
     << run.trace_passes
     << " serial passes per surface, recorded on this machine (shared with other work while recorded)"
     << (other_machines.empty()
             ? std::string(". ")
             : ". **The measured sets come from another machine** (" + other_machines +
                   "): the trace scale absorbs a uniform speed ratio between the two, not a difference in "
                   "caches, locks or wake-ups; the constants come from " +
                   (run.constants_file.empty() ? std::string("this machine") : "--calibration " + run.constants_file) +
                   ". ")
     << "The old model is the same simulator without the terms added here (cache affinity, lock hand-off to a "
        "sleeping waiter, per-frame wake-up skew) and without interference. Error = (predicted − measured) / "
        "measured.\n\n## Summary\n\n"
     << summary.markdown()
     << "\n## Ratios (every set held out)\n\nWhat survives a machine whose speed changes: "
        "per cell the paired ratio the main job measured (rounds in random order, its 95 % interval) against the "
        "ratio of two simulated times. The trace scale cancels, so no measured time enters the prediction. Error "
        "vs interval = 0 when the prediction lies inside the measured interval, else its error against the nearer "
        "bound.\n\n"
     << ratio_summary.markdown() << "\n## Stealing against the queue\n\n"
     << gap.markdown() << "\n## The model's constants\n\n"
     << describe(run.constants);
  if (run.affinity) {
    md << "\nAffinity measurement (" << run.calibration_set->path << ", P = 2, " << run.affinity_repeats
       << " paired repeats, thread CPU time in items, frames 1..F−1): kept lists "
       << report::fixed_text(median(run.affinity->kept_busy_ms), 1) << " ms, shuffled "
       << report::fixed_text(median(run.affinity->shuffled_busy_ms), 1) << " ms (medians); "
       << report::fixed_text(100 * run.affinity->moved_fraction, 1) << " % of item runs changed worker; penalty "
       << report::fixed_text(100 * run.affinity->penalty, 1) << " % of a moved item's cost ("
       << report::fixed_text(run.affinity->penalty_ns_per_moved_item, 0) << " ns per moved item); per repeat:";
    for (double p : run.affinity->penalty_per_repeat) md << ' ' << report::fixed_text(100 * p, 1) << " %";
    md << ".\n";
  }
  md << "\nASSUMED, not measured: the idle-round pause and each worker beyond 2 (see the table above)"
     << (run.constants.affinity_measured ? "" : ", and the affinity penalty")
     << ". Workers P > 2 are not validated here: "
        "on a 2-core machine they share cores, which the simulator (one core per worker) does not model.\n"
     << "\n## Every cell\n\n"
     << cells.markdown() << "\n## Every ratio\n\n"
     << ratio_cells.markdown();
  dir.write("validation.md", md.str());
  dir.write("validation.csv", cells.csv());
  report::Json doc = report::document("frontsteal-paper", 1, "validation", FRONTSTEAL_GIT_COMMIT);
  doc["machine"] = run.machine;
  doc["measured_on"] = report::Json::array();
  for (const MeasuredSet& s : run.sets) doc["measured_on"].push_back({{"set", s.name}, {"machine", s.machine}});
  doc["calibration_set"] = run.calibration_set->name;
  doc["trace_scale"] = run.trace_scale;
  doc["trace_passes"] = run.trace_passes;
  doc["threads"] = run.threads;
  doc["constants"] = {
      {"lock_wake_ns", run.constants.lock_wake_ns},           {"wake_skew_ns", run.constants.wake_skew_ns},
      {"affinity_penalty", run.constants.affinity_penalty},   {"affinity_measured", run.constants.affinity_measured},
      {"lock_handoff_ns", run.constants.lock_handoff_ns},     {"line_transfer_ns", run.constants.line_transfer_ns},
      {"idle_round_ns_assumed", run.constants.idle_round_ns}, {"microbenchmarks_assumed", run.constants.assumed}};
  if (run.affinity) {
    doc["affinity"] = {{"kept_busy_ms", run.affinity->kept_busy_ms},
                       {"shuffled_busy_ms", run.affinity->shuffled_busy_ms},
                       {"penalty_per_repeat", run.affinity->penalty_per_repeat},
                       {"moved_fraction", run.affinity->moved_fraction},
                       {"penalty", run.affinity->penalty},
                       {"penalty_ns_per_moved_item", run.affinity->penalty_ns_per_moved_item}};
  }
  doc["summary"] = summary.json();
  doc["stealing_vs_queue"] = gap.json();
  doc["ratio_summary"] = ratio_summary.json();
  doc["ratios"] = ratio_cells.json();
  doc["cells"] = cells.json();
  dir.write_json("validation.json", doc);
  if (!quiet) std::cout << summary.terminal() << '\n' << ratio_summary.terminal() << '\n' << gap.terminal();
  std::cout << "wrote " << dir.file("validation.md").string() << ", validation.json, validation.csv\n";
}

}  // namespace frontsteal::papers
