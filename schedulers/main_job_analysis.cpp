// main_job_analysis.cpp — the main job's analysis (main_job_analysis.hpp): verdicts and noise, the camera
// path's line, the round-robin cost spread and the summary lines.
#include "schedulers/main_job_analysis.hpp"

#include <unistd.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "core/machine_info.hpp"
#include "reporting/table.hpp"

namespace frontsteal::main_job {

namespace report = frontsteal::report;

namespace {

using frontsteal::cpu_model;
using frontsteal::median;

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

}  // namespace

std::string ShownComparison::verdict_text() const {
  std::string v = st::to_string(c.verdict);
  if (c.verdict != st::Verdict::kTooFewRepeats) v += " " + std::string(c.effect_pct >= 0 ? "+" : "") + fixed(c.effect_pct, 1) + " %";
  return reliable ? v : "unreliable (" + v + ")";
}

std::string ShownComparison::interval_text() const {
  return fixed(c.ratio.median, 3) + " [" + fixed(c.ratio.low, 3) + ", " + fixed(c.ratio.high, 3) + "]";
}

report::Json ShownComparison::json() const {
  return {{"ratio_median", c.ratio.median}, {"ci95_low", c.ratio.low}, {"ci95_high", c.ratio.high}, {"pairs", c.pairs},
          {"effect_pct", c.effect_pct}, {"verdict", reliable ? st::to_string(c.verdict) : "unreliable"},
          {"verdict_if_reliable", st::to_string(c.verdict)}, {"reliable", reliable}};
}

std::vector<double> frame_medians(const std::vector<std::vector<double>>& per_repeat, int frames) {
  std::vector<double> out;
  for (int f = 0; f < frames; ++f) {
    std::vector<double> v;
    for (const auto& rep : per_repeat) v.push_back(rep[f]);
    out.push_back(median(v));
  }
  return out;
}

namespace {

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
  a.spread_diagnosis = nz::diagnose_spread(m.serial_path_ms, m.serial_probe, o.noise.spread, m.serial_pass_usage);
  if (a.serial_spread > o.noise.spread) {
    a.noise_warnings.push_back("the serial loop's repeats spread by " + fixed(100 * a.serial_spread, 1) +
                               " % (max/min - 1; threshold " + fixed(100 * o.noise.spread, 1) + " %); " +
                               a.spread_diagnosis.line);
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
         << " % (workers pinned: " << (o.pin ? "yes, --pin" : "no") << "); " << a.spread_diagnosis.line;
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

}  // namespace

Analysis analyze(const Measured& m) {
  Analysis a;
  judge_rows(m, a);
  cost_spreads(m, a);
  summary_lines(m, a);
  return a;
}

}  // namespace frontsteal::main_job
