// main_job_report.cpp — the main job's analysis and reporting (main_job_report.hpp): verdicts and noise,
// the round-robin cost spread, the shown table (terminal, markdown), the data table (CSV, JSON rows),
// frontsteal.json (nlohmann, schema in docs/results-schema.md) and the gnuplot script.
#include "schedulers/main_job_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>

#include "core/machine_info.hpp"
#include "core/paired_comparison.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "schedulers/round_robin_spread.hpp"
#include "schedulers/static_assignment.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif

namespace frontsteal::main_job {

namespace st = frontsteal::stats;
namespace report = frontsteal::report;

namespace {

using frontsteal::cpu_model;
using frontsteal::median;
using report::Json;

constexpr const char* kProgram = "frontsteal";
// frontsteal.json's schema (docs/results-schema.md). 2: the common header of reporting/ (schema 1, written by
// hand, had no schema_version or program); every key of schema 1 is kept.
constexpr int kSchemaVersion = 2;

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// One comparison as the table shows it: the verdict, or "unreliable (verdict)" when the noise monitor says
// the machine was not ours while it was measured.
struct ShownComparison {
  st::Comparison c;
  bool reliable = true;
  std::string noise_reason;  // why not reliable
  std::string verdict_text() const {
    std::string v = st::to_string(c.verdict);
    if (c.verdict != st::Verdict::kTooFewRepeats) v += " " + std::string(c.effect_pct >= 0 ? "+" : "") + fixed(c.effect_pct, 1) + " %";
    return reliable ? v : "unreliable (" + v + ")";
  }
  std::string interval_text() const {
    return fixed(c.ratio.median, 3) + " [" + fixed(c.ratio.low, 3) + ", " + fixed(c.ratio.high, 3) + "]";
  }
  Json json() const {
    return {{"ratio_median", c.ratio.median}, {"ci95_low", c.ratio.low}, {"ci95_high", c.ratio.high}, {"pairs", c.pairs},
            {"effect_pct", c.effect_pct}, {"verdict", reliable ? st::to_string(c.verdict) : "unreliable"},
            {"verdict_if_reliable", st::to_string(c.verdict)}, {"reliable", reliable}};
  }
};

Json usage_json(const nz::Usage& u, const nz::Thresholds& t) {
  return {{"wall_s", u.wall_s}, {"windows", u.windows}, {"ticks", u.total_ticks}, {"other_share", u.other_share()},
          {"steal_share", u.steal_share()}, {"busy", nz::assess(u, t).busy}};
}

// {"worst", "worst_frame", "median", "per_frame"}; infinity (a worker with nothing) is null.
Json spread_json(const sc::CostSpread& c) {
  auto number = [](double v) { return std::isinf(v) ? Json(nullptr) : Json(v); };
  Json per_frame = Json::array();
  for (double v : c.per_frame) per_frame.push_back(number(v));
  return {{"worst", number(c.worst)}, {"worst_frame", c.worst_frame}, {"median", number(c.median)}, {"per_frame", per_frame}};
}

struct Row {
  const Cell* cell = nullptr;
  double path_ms = 0, fps = 0, speedup = 0, ideal_pct = 0, utilization = 0, imbalance_mean = 0;
  double cpu_pct = 0, off_cpu_pct = 0, spread_pct = 0;
  ShownComparison vs_serial;
  std::optional<ShownComparison> vs_queue;  // absent for queue-mutex itself, or when it was not run
};

struct SpreadRow {
  WorkerId p;
  sc::CostSpread measured, estimated;
  std::optional<sc::CostSpread> busy;  // from the round-robin row, when it ran at this P
};

// Everything the table, the files and the closing lines say.
struct Analysis {
  double t1_ms = 0, serial_spread = 0;
  nz::Usage before_usage, during_usage, after_usage;
  std::vector<std::string> noise_warnings;  // run-wide reasons: every verdict is unreliable
  std::vector<Row> rows;
  std::size_t verdicts = 0, unreliable = 0;
  bool problems = false;
  std::vector<SpreadRow> spreads;
  double co_runner_core_share = 0;
  std::uint64_t serial_inconsistencies = 0, capped_total = 0, capped_max = 0;
  std::string machine, path_line, spread_line, noise_line, spread_summary, interference_line, warning,
      tessellation_audit, child_note;
};

std::vector<double> frame_medians(const std::vector<std::vector<double>>& per_repeat, int frames) {
  std::vector<double> out;
  for (int f = 0; f < frames; ++f) {
    std::vector<double> v;
    for (const auto& rep : per_repeat) v.push_back(rep[f]);
    out.push_back(median(v));
  }
  return out;
}

// Noise: the machine before (loading and warm-up), during (every measured path, added up) and after; and
// the spread of the serial loop's repeats. Each makes every verdict unreliable; a busy machine during one
// cell's paths (or its reference's) makes that comparison unreliable.
void judge_rows(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.t1_ms = median(m.serial_path_ms);
  a.before_usage = nz::usage_between(m.at_start, m.measure_start);
  a.during_usage = nz::usage_between(m.measure_start, m.measure_end);
  a.after_usage = nz::usage_between(m.measure_end, m.at_end);
  nz::Usage serial_total;
  for (const nz::Usage& u : m.serial_usage) serial_total += u;
  a.serial_spread = nz::spread_of(m.serial_path_ms);
  if (const auto x = nz::assess(a.before_usage, o.noise); x.busy) a.noise_warnings.push_back("before the measurement: " + x.reason);
  if (const auto x = nz::assess(a.during_usage, o.noise); x.busy) a.noise_warnings.push_back("during the measurement: " + x.reason);
  if (const auto x = nz::assess(a.after_usage, o.noise); x.busy) a.noise_warnings.push_back("after the measurement: " + x.reason);
  if (a.serial_spread > o.noise.spread) {
    a.noise_warnings.push_back("the serial loop's repeats spread by " + fixed(100 * a.serial_spread, 1) +
                               " % (max/min - 1; threshold " + fixed(100 * o.noise.spread, 1) + " %)");
  }
  auto judge = [&](const std::vector<double>& candidate, const std::vector<double>& reference, nz::Usage usage) {
    ShownComparison sc_;
    sc_.c = st::compare_paired(candidate, reference);
    const nz::Assessment x = nz::assess(usage, o.noise);
    if (!a.noise_warnings.empty() || x.busy) {
      sc_.reliable = false;
      sc_.noise_reason = x.busy ? x.reason : a.noise_warnings.front();
    }
    return sc_;
  };
  auto queue_cell = [&](WorkerId p) -> const Cell* {
    for (const Cell& q : m.cells) {
      if (q.scheduler == "queue-mutex" && q.workers == p) return &q;
    }
    return nullptr;
  };
  for (const Cell& c : m.cells) {
    Row row{};
    row.cell = &c;
    row.path_ms = median(c.path_ms);
    row.fps = 1000.0 * o.frames / row.path_ms;
    row.speedup = a.t1_ms / row.path_ms;
    const double ideal_ms = a.t1_ms / std::min<double>(c.workers, m.cores);
    row.ideal_pct = 100.0 * ideal_ms / row.path_ms;
    row.utilization = c.available > 0 ? 100.0 * c.busy_over_available / c.available : 0;
    row.imbalance_mean = c.frames_run ? c.imbalance_sum / c.frames_run : 0;
    if (c.available > 0) {
      row.cpu_pct = 100.0 * static_cast<double>(c.totals.cpu_ns) / c.available;
      row.off_cpu_pct = 100.0 * static_cast<double>(std::max<std::int64_t>(0, c.totals.active_ns - c.totals.cpu_ns)) /
                        c.available;
    }
    row.spread_pct = 100.0 * nz::spread_of(c.path_ms);
    nz::Usage with_serial = c.usage;
    with_serial += serial_total;
    row.vs_serial = judge(c.path_ms, m.serial_path_ms, with_serial);
    ++a.verdicts;
    if (!row.vs_serial.reliable) ++a.unreliable;
    if (const Cell* q = queue_cell(c.workers); q && q != &c) {
      nz::Usage with_queue = c.usage;
      with_queue += q->usage;
      row.vs_queue = judge(c.path_ms, q->path_ms, with_queue);
      ++a.verdicts;
      if (!row.vs_queue->reliable) ++a.unreliable;
    }
    a.rows.push_back(row);
    if (c.failed()) a.problems = true;
  }
}

// The camera path, and how much a few surfaces dominate: the 16 costliest surfaces' share of a frame's
// estimated cost.
std::string path_line(const Measured& m) {
  const Options& o = m.o;
  std::ostringstream line;
  line << "camera path: " << ts::name(o.path);
  if (o.path == ts::CameraPathKind::dense_zoom) {
    const glm::dvec3 c = m.dense.box.centre();
    line << " (ends at the densest region: " << m.dense.surfaces << " surfaces centred in one grid cell of edge "
         << fixed(m.dense.cell_edge, 2) << " (the median control-box diagonal), around (" << fixed(c.x, 1) << ", "
         << fixed(c.y, 1) << ", " << fixed(c.z, 1) << "), box diagonal "
         << fixed(glm::length(m.dense.box.hi - m.dense.box.lo), 2) << ")";
  }
  double top_max = 0;
  int top_frame = 0;
  for (int f = 0; f < o.frames; ++f) {
    std::vector<double> c = m.item_estimate[f];
    const std::size_t k = std::min<std::size_t>(16, c.size());
    std::partial_sort(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(k), c.end(), std::greater<>());
    double top = 0, total = 0;
    for (std::size_t i = 0; i < c.size(); ++i) (i < k ? top : total) += c[i];
    total += top;
    if (total > 0 && top / total > top_max) {
      top_max = top / total;
      top_frame = f;
    }
  }
  line << "; the 16 costliest surfaces carry up to " << fixed(100 * top_max, 1)
       << " % of a frame's estimated cost (frame " << top_frame << ")";
  return line.str();
}

// The round-robin cost spread per P >= 2 (round_robin_spread.hpp), and its summary lines.
void cost_spreads(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  for (WorkerId p : o.threads) {
    if (p < 2) continue;
    SpreadRow r{p, sc::round_robin_spread(m.item_ns, p), sc::round_robin_spread(m.item_estimate, p), std::nullopt};
    for (const Cell& c : m.cells) {
      if (c.scheduler != "round-robin" || c.workers != p || c.busy_ratio.empty()) continue;
      r.busy = sc::summarize_spread(frame_medians(c.busy_ratio, o.frames));  // median over repeats, per frame
    }
    a.spreads.push_back(std::move(r));
  }
  using sc::ratio_text;
  std::ostringstream s;
  s << "round-robin cost spread (max/min over workers of the per-frame cost, item i on worker i mod P; "
       "worst frame / median over frames; paper §3: 1:50 for static schemes):";
  if (a.spreads.empty()) s << " no P >= 2 was run";
  for (const SpreadRow& r : a.spreads) {
    s << "\n  P=" << r.p << ": serial loop's measured per-item times dealt round robin " << ratio_text(r.measured.worst)
      << " (frame " << r.measured.worst_frame << ") / " << ratio_text(r.measured.median) << "; cost estimates "
      << ratio_text(r.estimated.worst) << " / " << ratio_text(r.estimated.median) << "; round-robin row's busy time "
      << (r.busy ? ratio_text(r.busy->worst) + " / " + ratio_text(r.busy->median) : std::string("not run"));
  }
  a.spread_summary = s.str();
}

// The one-line summaries: spread of the repeats, noise, interference, tessellation audit, the LLVM child,
// and the noise warning (empty when every verdict is reliable).
void summary_lines(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.machine = cpu_model() + ", " + std::to_string(m.cores) + " hardware threads";
  a.path_line = path_line(m);
  std::vector<double> cell_spreads;
  for (const Row& r : a.rows) cell_spreads.push_back(r.spread_pct);
  std::ostringstream spread;
  spread << "spread of the repeats (max/min - 1): serial loop " << fixed(100 * a.serial_spread, 1)
         << " %; schedulers: median " << fixed(median(cell_spreads), 1) << " %, max "
         << fixed(cell_spreads.empty() ? 0.0 : *std::max_element(cell_spreads.begin(), cell_spreads.end()), 1)
         << " % (workers pinned: " << (o.pin ? "yes, --pin" : "no") << ")";
  a.spread_line = spread.str();
  std::ostringstream noise;
  noise << "noise monitor: other processes / steal, as a share of the machine: before "
        << fixed(100 * a.before_usage.other_share(), 1) << " / " << fixed(100 * a.before_usage.steal_share(), 1)
        << " %, during " << fixed(100 * a.during_usage.other_share(), 1) << " / "
        << fixed(100 * a.during_usage.steal_share(), 1) << " %, after " << fixed(100 * a.after_usage.other_share(), 1)
        << " / " << fixed(100 * a.after_usage.steal_share(), 1) << " %; load average " << fixed(m.at_start.load1, 2)
        << " before, " << fixed(m.at_end.load1, 2) << " after (thresholds: " << fixed(100 * o.noise.other_share, 0)
        << " % busy, " << fixed(100 * o.noise.spread, 0) << " % spread)";
  a.noise_line = noise.str();
  nz::Usage cells_usage;
  for (const Cell& c : m.cells) cells_usage += c.usage;
  const double ticks_per_s = static_cast<double>(sysconf(_SC_CLK_TCK));
  a.co_runner_core_share =
      cells_usage.wall_s > 0 ? static_cast<double>(cells_usage.known_ticks) / (cells_usage.wall_s * ticks_per_s) : 0;
  a.interference_line = "interference: off";
  if (o.interference) {
    a.interference_line = "interference: ON, a co-runner child process busy-looping " + o.interference->describe() +
                          ", during every scheduler row (paused during the serial loop: T1 is undisturbed); it used " +
                          fixed(100 * a.co_runner_core_share, 1) + " % of one core while the schedulers ran " +
                          "(its own CPU time from /proc/<pid>/stat, reported here and not counted as noise)";
  }
  if (a.unreliable > 0) {
    std::ostringstream warning;
    warning << "WARNING: noisy machine: " << a.unreliable << " of " << a.verdicts
            << " verdicts are marked unreliable. Reasons:\n";
    for (const auto& w : a.noise_warnings) warning << "  - " << w << "\n";
    std::size_t cell_flags = 0;
    for (const Row& r : a.rows) {
      if (!r.vs_serial.reliable && r.vs_serial.noise_reason != (a.noise_warnings.empty() ? "" : a.noise_warnings.front())) {
        if (cell_flags++ < 5) {
          warning << "  - while " << r.cell->scheduler << " P=" << r.cell->workers << " or its reference ran: "
                  << r.vs_serial.noise_reason << "\n";
        }
      }
    }
    if (cell_flags > 5) warning << "  - ... and " << cell_flags - 5 << " more scheduler/P cells\n";
    warning << "Re-run on a quiet machine before drawing conclusions from these verdicts.\n";
    a.warning = warning.str();
  }
  for (int f = 0; f < o.frames; ++f) {
    a.serial_inconsistencies += m.wl.serial_inconsistencies[f];
    a.capped_total += m.wl.serial_capped[f];
    a.capped_max = std::max(a.capped_max, m.wl.serial_capped[f]);
  }
  if (a.serial_inconsistencies > 0) a.problems = true;
  // One line that says what "audit ok" covers, and what it found.
  std::ostringstream audit;
  audit << "tessellation audit (every surface of every frame, every run: trimmed pieces tiled exactly, "
           "(u, v) area = trim-loop area): "
        << a.serial_inconsistencies << " inconsistencies in the serial loop; surfaces held at the "
        << m.wl.settings.max_steps << "-step cap (deviation may exceed " << o.tolerance << " px there): "
        << a.capped_total << " surface-frames, at most " << a.capped_max << " per frame";
  a.tessellation_audit = audit.str();
  std::ostringstream child;  // how openmp-static-steal ran, and the proof that static_steal was in effect
  for (const Cell& c : m.cells) {
    if (c.child) {
      child << sc::kLlvmOpenMpName << " P=" << c.workers << ": child process " << sc::llvm_openmp_child_path()
            << " (clang++-14, libomp; per-item code compiled by clang), " << c.child->ready_line()
            << "; steals = chunks run off their static owner\n";
    }
  }
  a.child_note = child.str();
}

Analysis analyze(const Measured& m) {
  Analysis a;
  judge_rows(m, a);
  cost_spreads(m, a);
  summary_lines(m, a);
  return a;
}

// The table as the terminal and frontsteal.md show it: the serial loop first, then every scheduler and P,
// then the cells that could not run. Existing columns first, in their old order; the added ones (cpu, off-cpu,
// the two comparisons) after lock waits, audit last.
report::Table shown_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"}, {"scheduler", "scheduler", text}, {"frames_per_s", "frames/s"},
                   {"speedup", "speed-up"}, {"ideal_pct", "% of ideal"}, {"utilization_pct", "utilization"},
                   {"imbalance_mean", "imbalance"}, {"steals", "steals (failed)"}, {"lock_waits", "lock waits"},
                   {"cpu_pct", "cpu"}, {"off_cpu_pct", "off-cpu"}, {"ratio_vs_serial", "T_P/T1 [95% CI]", text},
                   {"verdict_vs_serial", "vs serial", text}, {"ratio_vs_queue", "T_P/T_queue [95% CI]", text},
                   {"verdict_vs_queue", "vs queue-mutex", text}, {"audit", "audit", text}});
  t.add_row({1, "serial loop (T1)", fixed(1000.0 * m.o.frames / a.t1_ms, 2), "1.00", "100.0", "-", "-", "-", "-", "-",
             "-", "reference", "-", "-", "-", "-"});
  for (const Row& r : a.rows) {
    const Cell& c = *r.cell;
    const std::uint64_t failed = c.totals.steal_attempts - c.totals.steals_succeeded;
    t.add_row({c.workers, c.scheduler, fixed(r.fps, 2), fixed(r.speedup, 2), fixed(r.ideal_pct, 1),
               fixed(r.utilization, 1) + "%", fixed(r.imbalance_mean, 3),
               std::to_string(c.totals.steals_succeeded) + " (" + std::to_string(failed) + ")", c.totals.lock_waits,
               fixed(r.cpu_pct, 1) + "%", fixed(r.off_cpu_pct, 1) + "%", r.vs_serial.interval_text(),
               r.vs_serial.verdict_text(), r.vs_queue ? r.vs_queue->interval_text() : "-",
               r.vs_queue ? r.vs_queue->verdict_text() : (c.scheduler == "queue-mutex" ? "reference" : "-"),
               c.failed() ? "FAILED" : "ok"});
  }
  for (const Cell& c : m.not_available) {
    t.add_row({c.workers, c.scheduler, "not available: " + c.unavailable, "-", "-", "-", "-", "-", "-", "-", "-", "-",
               "-", "-", "-", "-"});
  }
  return t;
}

// The data (frontsteal.csv, and each row of frontsteal.json's results[]): full precision, the serial loop first.
report::Table data_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"}, {"scheduler", "scheduler", text}, {"path_ms", "path (ms)"},
                   {"frames_per_s", "frames/s"}, {"speedup", "speed-up"}, {"ideal_pct", "% of ideal"},
                   {"utilization_pct", "utilization (%)"}, {"imbalance_mean", "imbalance"},
                   {"imbalance_max", "max imbalance"}, {"steals", "steals"}, {"steal_attempts", "steal attempts"},
                   {"lock_waits", "lock waits"}, {"lock_wait_ms", "lock wait (ms)"}, {"setup_ms", "set-up (ms)"},
                   {"audit_failures", "audit failures"}, {"triangle_mismatches", "triangle mismatches"},
                   {"tessellation_inconsistencies", "tessellation inconsistencies"}, {"cpu_pct", "cpu (%)"},
                   {"off_cpu_pct", "off-cpu (%)"}, {"path_spread_pct", "spread (%)"},
                   {"ratio_vs_serial", "T_P/T1"}, {"ratio_vs_serial_ci_low", "T_P/T1 low"},
                   {"ratio_vs_serial_ci_high", "T_P/T1 high"}, {"verdict_vs_serial", "vs serial", text},
                   {"effect_vs_serial_pct", "effect vs serial (%)"}, {"ratio_vs_queue", "T_P/T_queue"},
                   {"ratio_vs_queue_ci_low", "T_P/T_queue low"}, {"ratio_vs_queue_ci_high", "T_P/T_queue high"},
                   {"verdict_vs_queue", "vs queue-mutex", text}, {"effect_vs_queue_pct", "effect vs queue-mutex (%)"},
                   {"reliable", "reliable", text}});
  auto num = [](double v) { return report::Cell::fixed(v, 3); };
  const report::Cell none = report::Cell::empty();
  std::vector<report::Cell> serial{1, "serial", num(a.t1_ms), num(1000.0 * m.o.frames / a.t1_ms), 1, 100};
  serial.insert(serial.end(), 8, none);
  serial.insert(serial.end(), {0, 0, a.serial_inconsistencies, none, none, num(100 * a.serial_spread)});
  serial.insert(serial.end(), 10, none);
  serial.emplace_back(a.noise_warnings.empty());
  t.add_row(std::move(serial));
  auto comparison = [&](std::vector<report::Cell>& row, const ShownComparison* c) {
    if (!c) {
      row.insert(row.end(), 5, none);
      return;
    }
    row.insert(row.end(), {num(c->c.ratio.median), num(c->c.ratio.low), num(c->c.ratio.high),
                           c->reliable ? st::to_string(c->c.verdict) : "unreliable", num(c->c.effect_pct)});
  };
  for (const Row& r : a.rows) {
    const Cell& c = *r.cell;
    std::vector<report::Cell> row{c.workers, c.scheduler, num(r.path_ms), num(r.fps), num(r.speedup), num(r.ideal_pct),
                                  num(r.utilization), num(r.imbalance_mean), num(c.imbalance_max),
                                  c.totals.steals_succeeded, c.totals.steal_attempts, c.totals.lock_waits,
                                  num(c.totals.lock_wait_ns / 1e6), num(c.setup_ms), c.audit_failures,
                                  c.triangle_mismatches, c.tessellation_inconsistencies, num(r.cpu_pct),
                                  num(r.off_cpu_pct), num(r.spread_pct)};
    comparison(row, &r.vs_serial);
    comparison(row, r.vs_queue ? &*r.vs_queue : nullptr);
    row.emplace_back(r.vs_serial.reliable && (!r.vs_queue || r.vs_queue->reliable));
    t.add_row(std::move(row));
  }
  return t;
}

// frontsteal.json: the set-up, the round-robin spread, the noise, the serial loop, and per scheduler and P the
// data table's row with the structured values added (comparisons, noise, per worker, per repeat, per frame).
Json results_json(const Measured& m, const Analysis& a, const report::Table& data) {
  const Options& o = m.o;
  Json js = report::document(kProgram, kSchemaVersion, "measured", FRONTSTEAL_GIT_COMMIT);
  js["machine"] = a.machine;
  js["scene"] = o.scene;
  js["surfaces"] = m.wl.model.surfaces.size();
  js["frames"] = o.frames;
  js["repeats"] = o.repeats;
  js["tolerance_px"] = o.tolerance;
  js["image"] = {o.width, o.height};
  js["hardware_threads"] = m.cores;
  js["repeats_note"] = m.repeats_note;
  js["pinned"] = o.pin;
  js["path"] = ts::name(o.path);
  js["path_note"] = a.path_line;
  if (o.interference) {
    js["interference"] = {{"on", true}, {"duty_pct", 100 * o.interference->duty},
                          {"setup", o.interference->pinned ? "pinned" : "unpinned"}, {"period_ms", 10},
                          {"co_runner_cpu", m.co_runner_cpu}, {"co_runner_core_share_measured", a.co_runner_core_share},
                          {"serial_loop", "co-runner paused"}, {"note", a.interference_line}};
  } else {
    js["interference"] = {{"on", false}};
  }
  Json spreads = Json::array();
  for (const SpreadRow& r : a.spreads) {
    spreads.push_back({{"workers", r.p}, {"serial_item_times", spread_json(r.measured)},
                       {"estimates", spread_json(r.estimated)},
                       {"round_robin_busy", r.busy ? spread_json(*r.busy) : Json(nullptr)}});
  }
  js["round_robin_spread"] = spreads;
  js["noise"] = {{"before", usage_json(a.before_usage, o.noise)}, {"during", usage_json(a.during_usage, o.noise)},
                 {"after", usage_json(a.after_usage, o.noise)}, {"co_runner_share_during", a.during_usage.known_share()},
                 {"load1_before", m.at_start.load1}, {"load1_after", m.at_end.load1},
                 {"serial_spread_pct", 100 * a.serial_spread}, {"busy_threshold_pct", 100 * o.noise.other_share},
                 {"spread_threshold_pct", 100 * o.noise.spread}, {"verdicts", a.verdicts},
                 {"unreliable_verdicts", a.unreliable}, {"warnings", a.noise_warnings}};
  js["serial"] = {{"path_ms", a.t1_ms}, {"path_ms_per_repeat", m.serial_path_ms},
                  {"triangles_per_frame", m.wl.serial_triangles},
                  {"inconsistent_surfaces_per_frame", m.wl.serial_inconsistencies},
                  {"capped_surfaces_per_frame", m.wl.serial_capped}, {"max_steps", m.wl.settings.max_steps},
                  {"frame_ms_median", frame_medians(m.serial_frame_ms, o.frames)}};
  const Json rows = data.json();  // [0] is the serial loop, already under "serial"
  Json results = Json::array();
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const Row& r = a.rows[i];
    const Cell& c = *r.cell;
    Json row = rows.at(i + 1);
    row["items_stolen"] = c.totals.items_stolen;
    row["vs_serial"] = r.vs_serial.json();
    row["vs_queue_mutex"] = r.vs_queue ? r.vs_queue->json() : Json(nullptr);
    row["noise"] = usage_json(c.usage, o.noise);
    Json per_worker = Json::array();
    for (const WorkerFrameStats& ws : c.per_worker) {
      per_worker.push_back({{"items", ws.items_processed}, {"busy_ms", ws.busy_ns / 1e6}, {"cpu_ms", ws.cpu_ns / 1e6},
                            {"active_ms", ws.active_ns / 1e6}});
    }
    row["per_worker"] = per_worker;
    row["path_ms_per_repeat"] = c.path_ms;
    row["frame_ms_median"] = frame_medians(c.frame_ms, o.frames);
    results.push_back(std::move(row));
  }
  js["results"] = results;
  Json not_available = Json::array();
  for (const Cell& c : m.not_available) {
    not_available.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"reason", c.unavailable}});
  }
  js["not_available"] = not_available;
  Json children = Json::array();
  for (const Cell& c : m.cells) {
    if (c.child) children.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"ready", c.child->ready_line()}});
  }
  js["child_processes"] = children;
  return js;
}

// A string for a gnuplot double-quoted literal: quotes and backslashes escaped, control characters dropped.
std::string gnuplot_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out;
}

// Plots: speed-up against P (one line per scheduler, the ideal dashed), and frame time along the path at the
// largest P not above the core count. The data and the script are always written; gnuplot runs unless --no-plot.
void write_plots(const Measured& m, const Analysis& a, const report::ResultsDir& dir) {
  const Options& o = m.o;
  std::ostringstream dat;
  for (const auto& name : o.schedulers) {
    dat << "\"" << name << "\"\n";
    for (const Row& r : a.rows) {
      if (r.cell->scheduler == name) dat << r.cell->workers << ' ' << r.speedup << '\n';
    }
    dat << "\n\n";
  }
  dir.write("frontsteal-speedup.dat", dat.str());
  WorkerId best_p = 1;
  for (WorkerId p : o.threads) {
    if (p <= m.cores) best_p = std::max(best_p, p);
  }
  std::ostringstream frames;
  auto block = [&](const std::string& title, const std::vector<std::vector<double>>& per_repeat) {
    frames << "\"" << title << "\"\n";
    const std::vector<double> med = frame_medians(per_repeat, o.frames);
    for (int f = 0; f < o.frames; ++f) frames << f << ' ' << med[f] << '\n';
    frames << "\n\n";
  };
  block("serial loop", m.serial_frame_ms);
  int blocks = 1;
  for (const Row& r : a.rows) {
    if (r.cell->workers != best_p) continue;
    block(r.cell->scheduler + " P=" + std::to_string(best_p), r.cell->frame_ms);
    ++blocks;
  }
  dir.write("frontsteal-frames.dat", frames.str());
  const WorkerId max_p = *std::max_element(o.threads.begin(), o.threads.end());
  std::ostringstream gp;
  gp << "# gnuplot script written by frontsteal; run from " << o.out << ": gnuplot frontsteal.gp\n"
     << "set terminal pngcairo size 1200,760 font 'sans,10'\nset key outside right top\nset grid\n"
     << "set output 'frontsteal-speedup.png'\n"
     << "set title \"Tessellation speed-up over the serial loop (measured): " << gnuplot_text(o.scene) << ", "
     << m.wl.model.surfaces.size() << " surfaces\\n" << gnuplot_text(a.machine) << "\"\n"
     << "set xlabel 'workers P'\nset ylabel 'speed-up (T1 / T_P)'\nset xrange [0.5:" << max_p + 0.5 << "]\n"
     << "set yrange [0:*]\n"
     << "plot for [i=0:" << o.schedulers.size() - 1 << "] 'frontsteal-speedup.dat' index i using 1:2 with "
        "linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1), (x <= " << m.cores << " ? x : " << m.cores
     << ") with lines dashtype 2 lc 'black' title 'ideal'\n"
     << "set output 'frontsteal-frames.png'\n"
     << "set title 'Frame time along the camera path (measured), P = " << best_p
     << (o.path == ts::CameraPathKind::orbit_then_zoom
             ? " (frames 0-" + std::to_string(o.frames / 2 - 1) + " orbit, then zoom)"
             : std::string(" (path ") + ts::name(o.path) + ")")
     << (o.interference ? ", interference on" : "") << "'\n"
     << "set xlabel 'frame'\nset ylabel 'ms'\nset autoscale x\nset yrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1 << "] 'frontsteal-frames.dat' index i using 1:2 with linespoints "
        "lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)\n";
  dir.write("frontsteal.gp", gp.str());
  if (o.plot) dir.plot("frontsteal.gp");
}

// The heading lines above the table (terminal).
std::string terminal_heading(const Measured& m, const Analysis& a) {
  const Options& o = m.o;
  std::ostringstream s;
  s << "\nfrontsteal: " << o.scene << ", " << m.wl.model.surfaces.size() << " surfaces, " << o.frames << " frames x "
    << o.repeats << " repeats (medians), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height << "\n"
    << "machine: " << a.machine << " (measured, not simulated)\n"
    << "ideal = T1 / min(P, " << m.cores << "); utilization = busy / (wall x P), summed over every frame; "
    << "imbalance = max/mean busy per frame, averaged; cpu, off-cpu = workers' thread CPU time and time "
    << "in the frame without a CPU, over wall x P\n"
    << "repeats: " << o.repeats << " (" << m.repeats_note << "); T_P/T_ref = median of per-repeat ratios, "
    << "95 % bootstrap interval; verdict at 95 %, effect = change in path time\n"
    << a.path_line << "\n" << a.interference_line << "\n" << a.spread_summary << "\n\n";
  return s.str();
}

std::string markdown_report(const Measured& m, const Analysis& a, const std::string& table) {
  const Options& o = m.o;
  std::ostringstream md;
  md << "# frontsteal main job (measured)\n\n"
     << "Scene `" << o.scene << "` (" << m.wl.model.surfaces.size() << " surfaces), " << o.frames
     << " frames along the camera path `" << ts::name(o.path) << "`, " << o.repeats
     << " interleaved repeats (medians), tolerance " << o.tolerance << " px, " << o.width << "x" << o.height
     << ". Machine: " << a.machine << ". Commit " << FRONTSTEAL_GIT_COMMIT << ".\n\n"
     << "Verdicts: median of the per-repeat ratios T_P[r] / T_ref[r] with its 95 % bootstrap interval; ahead / "
     << "behind when the interval lies below / above 1; effect = change in path time. cpu and off-cpu: the "
     << "workers' thread CPU time and their time in the frame without a CPU, over wall x P.\n\n"
     << "**" << a.path_line << "; " << a.interference_line << ".**\n\n```\n" << a.spread_summary << "\n```\n\n"
     << table << '\n' << a.child_note << (a.child_note.empty() ? "" : "\n") << a.tessellation_audit << ".\n\n"
     << a.spread_line << ".\n\n" << a.noise_line << ".\n";
  if (!a.warning.empty()) md << "\n**" << a.warning.substr(0, a.warning.find('\n')) << "**\n\n```\n" << a.warning << "```\n";
  return md.str();
}

// The audit failures, on stderr; true when there were any.
bool report_problems(const Measured& m, const Analysis& a) {
  if (!a.problems) return false;
  std::cerr << kProgram << ": AUDIT FAILED:\n";
  if (a.serial_inconsistencies > 0) {
    std::cerr << "  serial loop: " << a.serial_inconsistencies << " surface-frames fail the tessellation audit\n";
  }
  for (const Cell& c : m.cells) {
    if (c.failed()) {
      std::cerr << "  " << c.scheduler << " P=" << c.workers << ": " << c.audit_failures << " frames not exactly-once, "
                << c.triangle_mismatches << " triangle mismatches, " << c.tessellation_inconsistencies
                << " surface-frames failing the tessellation audit; first: " << c.first_problem << '\n';
    }
  }
  return true;
}
}  // namespace

int write_results(const Measured& m, double elapsed_s) {
  const Options& o = m.o;
  const Analysis a = analyze(m);
  const std::string table = shown_table(m, a).markdown();
  std::cout << terminal_heading(m, a) << table << '\n' << a.child_note << a.tessellation_audit << '\n'
            << a.spread_line << '\n' << a.noise_line << '\n';
  try {
    const report::ResultsDir dir(kProgram, o.out);
    const report::Table data = data_table(m, a);
    dir.write("frontsteal.md", markdown_report(m, a, table));
    dir.write("frontsteal.csv", data.csv());
    dir.write_json("frontsteal.json", results_json(m, a, data));
    write_plots(m, a, dir);
    std::cout << "\nwrote " << dir.file("frontsteal.json").string() << ", .csv, .md"
              << (o.plot ? ", frontsteal-speedup.png, frontsteal-frames.png" : "") << " ("
              << fixed(elapsed_s, 0) << " s)\n";
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  if (a.unreliable > 0) {
    // Last, on stdout and stderr, so it is the thing one sees.
    std::cout << '\n' << a.warning;
    std::cerr << kProgram << ": WARNING: noisy machine: " << a.unreliable << " of " << a.verdicts
              << " verdicts unreliable (reasons on stdout and in frontsteal.md)\n";
  }
  return report_problems(m, a) ? 1 : 0;
}


}  // namespace frontsteal::main_job
