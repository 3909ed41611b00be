// analysis.cpp — the main job's analysis (analysis.hpp): verdicts and noise, the camera
// path's line, the round-robin cost spread and the summary lines.
#include "schedulers/main_job/analysis.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include "measure/machine_info.hpp"
#include "reporting/table.hpp"

namespace frontsteal::main_job {

namespace report = frontsteal::report;

namespace {

using frontsteal::cpu_model;
using frontsteal::median;

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

}  // namespace

std::string ShownComparison::verdict_text() const {
  std::string v = measure::to_string(c.decision);
  if (c.chosen().valid)
    v += " " + std::string(c.chosen().effect_pct() >= 0 ? "+" : "") + fixed(c.chosen().effect_pct(), 1) + " %";
  return reliable ? v : "unreliable (" + v + ")";
}

std::string ShownComparison::interval_text() const {
  const measure::LogInterval& li = c.chosen();
  if (!li.valid) return "-";
  return fixed(li.ratio(), 3) + " [" + fixed(li.ratio_low(), 3) + ", " + fixed(li.ratio_high(), 3) + "]";
}

namespace {

report::Json interval_json(const measure::LogInterval& li) {
  if (!li.valid) return nullptr;
  return {{"ratio", li.ratio()},
          {"ci95_low", li.ratio_low()},
          {"ci95_high", li.ratio_high()},
          {"log_ratio", li.estimate},
          {"sd_per_round", li.sd},
          {"se", li.se},
          {"df", li.df}};
}

double finite_or(double v, double otherwise) { return std::isfinite(v) ? v : otherwise; }

// A path as the reports show it: relative to the working directory when it lies below it, so that a committed
// report names the repository's build folder rather than the machine it was made on.
std::string shown_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path cwd = std::filesystem::current_path(ec);
  if (ec) return path;
  const std::filesystem::path rel = std::filesystem::path(path).lexically_relative(cwd);
  if (rel.empty() || *rel.begin() == "..") return path;
  return rel.string();
}

// Surfaces re-tessellated per frame in the serial warm-up pass: with --reuse the frame's real work, without it
// every surface every frame.
std::string remade_line(const Options& o, const Workload& wl) {
  const std::size_t n = wl.prepared.size();
  std::uint64_t total = 0, lo = n, hi = 0;
  for (const std::uint64_t r : wl.serial_remade) total += r, lo = std::min<std::uint64_t>(lo, r), hi = std::max(hi, r);
  const double mean = wl.serial_remade.empty() ? 0.0 : static_cast<double>(total) / wl.serial_remade.size();
  if (!o.reuse) return "surfaces re-tessellated per frame: all " + std::to_string(n) + " (no --reuse)";
  return "surfaces re-tessellated per frame (--reuse; the serial pass along the path): mean " + fixed(mean, 0) +
         " of " + std::to_string(n) + " (" + fixed(100.0 * mean / std::max<std::size_t>(n, 1), 1) + " %), " +
         std::to_string(lo) + " to " + std::to_string(hi) + " (frame 0 makes every surface)";
}

std::string instances_text(const Options& o) {
  if (o.instance_frames <= 0) return "one instance of each scheduler for the whole run";
  return "a fresh instance of each scheduler every " + std::to_string(o.instance_frames) +
         " frames, its rounds one cluster of the cluster-robust error";
}

}  // namespace

report::Json ShownComparison::json() const {
  const measure::LogInterval& li = c.chosen();
  auto number = [&](double v) { return li.valid ? report::Json(v) : report::Json(nullptr); };  // no interval: null
  return {
      {"ratio", number(li.ratio())},
      {"ci95_low", number(li.ratio_low())},
      {"ci95_high", number(li.ratio_high())},
      {"pairs", c.rounds},
      {"rounds", c.rounds},
      {"blocks", c.blocks},
      {"clusters", c.clusters},
      {"effect_pct", number(li.effect_pct())},
      {"verdict", reliable ? measure::to_string(c.decision) : "unreliable"},
      {"verdict_if_reliable", measure::to_string(c.decision)},
      {"reliable", reliable},
      {"unreliable_reason", noise_reason},
      {"margin_pct", 100 * c.margin},
      {"differs", c.differs},
      {"interval", c.uses_adjusted ? "probe-adjusted t" : "raw t"},
      {"raw", interval_json(c.raw)},
      {"adjusted", interval_json(c.adjusted)},
      {"probe_slope", c.probe_slope},
      {"variance_removed", c.variance_removed},
      {"rounds_needed", c.decision == measure::Decision::kInconclusive ? report::Json(finite_or(c.rounds_needed, -1))
                                                                       : report::Json(nullptr)},
      {"mde80_pct", number(c.mde_pct)}};
}

bool CalibrationRow::found() const {
  const measure::LogInterval& li = result.c.chosen();
  return li.valid && (nominal > 0 ? li.low > 0 : nominal < 0 ? li.high < 0 : false);
}
bool CalibrationRow::covered() const {
  return result.c.chosen().valid && result.c.chosen().contains(std::log1p(realized));
}
bool CalibrationRow::right() const {
  const measure::Decision d = result.c.decision;
  return nominal > 0   ? d == measure::Decision::kSlower
         : nominal < 0 ? d == measure::Decision::kFaster
                       : d == measure::Decision::kEquivalent;
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

// What may invalidate a verdict, and only that: another process (or the hypervisor) took the machine while the
// pair's arms ran (their noise-monitor windows added up), an audit failed in either arm, or the co-runner did
// not run as asked. The machine before and after the measurement, and the spread of single serial passes, are
// reported as context: the paired rounds are what the verdicts rest on.
void judge_rows(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.t1_ms = median(m.serial_path_ms);
  a.before_usage = nz::usage_between(m.at_start, m.measure_start);
  a.during_usage = nz::usage_between(m.measure_start, m.measure_end);
  a.after_usage = nz::usage_between(m.measure_end, m.at_end);
  nz::Usage serial_total;
  for (const nz::Usage& u : m.serial_usage) serial_total += u;
  a.serial_spread = nz::spread_of(m.serial_path_ms);
  if (const auto x = nz::assess(a.before_usage, o.noise); x.busy)
    a.notes.push_back("before the measurement: " + x.reason);
  if (const auto x = nz::assess(a.after_usage, o.noise); x.busy)
    a.notes.push_back("after the measurement: " + x.reason);
  a.spread_diagnosis = nz::diagnose_spread(m.serial_path_ms, m.serial_probe, o.noise.spread, m.serial_pass_usage);
  if (o.interference) {
    nz::Usage cells_usage;
    for (const Cell& c : m.cells) cells_usage += c.usage;
    const double ticks_per_s = static_cast<double>(sysconf(_SC_CLK_TCK));
    const double share =
        cells_usage.wall_s > 0 ? static_cast<double>(cells_usage.known_ticks) / (cells_usage.wall_s * ticks_per_s) : 0;
    if (share < 0.5 * o.interference->duty) {
      a.noise_warnings.push_back("the interference co-runner used " + fixed(100 * share, 1) +
                                 " % of a core while the "
                                 "schedulers ran, less than half of the " +
                                 fixed(100 * o.interference->duty, 0) +
                                 " % asked: the interference was not what the run says");
    }
  }
  const measure::Settings settings = analysis_settings(o);
  auto judge = [&](const Cell& cand, const measure::ArmRounds& reference, nz::Usage usage, bool reference_failed) {
    ShownComparison sc_;
    sc_.c = measure::analyze_pairs(measure::pair_rounds(cand.rounds, reference), settings);
    const nz::Assessment x = nz::assess(usage, o.noise);
    if (!a.noise_warnings.empty()) {
      sc_.reliable = false;
      sc_.noise_reason = a.noise_warnings.front();
    } else if (x.busy) {
      sc_.reliable = false;
      sc_.noise_reason = "while this pair ran: " + x.reason;
    } else if (cand.failed() || reference_failed) {
      sc_.reliable = false;
      sc_.noise_reason = "an audit failed in this pair";
    }
    return sc_;
  };
  auto base_cell = [&](const std::string& name, WorkerId p) -> const Cell* {
    for (const Cell& q : m.cells) {
      if (q.role == ArmRole::kScheduler && q.scheduler == name && q.workers == p) return &q;
    }
    return nullptr;
  };
  for (const Cell& c : m.cells) {
    if (c.role != ArmRole::kScheduler) continue;
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
      row.off_cpu_pct =
          100.0 * static_cast<double>(std::max<std::int64_t>(0, c.totals.active_ns - c.totals.cpu_ns)) / c.available;
    }
    row.spread_pct = 100.0 * nz::spread_of(c.path_ms);
    nz::Usage with_serial = c.usage;
    with_serial += serial_total;
    row.vs_serial = judge(c, m.serial_rounds, with_serial, a.serial_inconsistencies > 0);
    ++a.verdicts;
    if (!row.vs_serial.reliable) ++a.unreliable;
    if (const Cell* q = base_cell("queue-mutex", c.workers); q && q != &c) {
      nz::Usage with_queue = c.usage;
      with_queue += q->usage;
      row.vs_queue = judge(c, q->rounds, with_queue, q->failed());
      ++a.verdicts;
      if (!row.vs_queue->reliable) ++a.unreliable;
    }
    a.rows.push_back(row);
    if (c.failed()) a.problems = true;
  }
  // The calibration arms against their base; the planted speed-up is the base against its +5 % arm.
  for (const Cell& c : m.cells) {
    if (c.role == ArmRole::kScheduler) continue;
    const Cell* base = base_cell(c.scheduler, c.workers);
    if (!base) continue;
    double log_sum = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < c.rounds.size(); ++k) {
      const double t = c.rounds.time[k], planted = c.round_planted_ms[k];
      if (t > planted && planted >= 0) {
        log_sum += std::log(t / (t - planted));
        ++n;
      }
    }
    const double realized = n ? std::expm1(log_sum / static_cast<double>(n)) : 0.0;
    nz::Usage usage = c.usage;
    usage += base->usage;
    CalibrationRow row{c.label,
                       c.workers,
                       c.planted,
                       c.role == ArmRole::kTwin ? 0.0 : realized,
                       judge(c, base->rounds, usage, base->failed()),
                       &c.rounds,
                       &base->rounds};
    a.calibration.push_back(row);
    if (c.failed()) a.problems = true;
    if (std::fabs(c.planted - 0.05) < 1e-9) {
      CalibrationRow speedup{base->scheduler + " against " + c.label + " (planted speed-up)",
                             c.workers,
                             -0.05,
                             1.0 / (1.0 + realized) - 1.0,
                             ShownComparison{},
                             &base->rounds,
                             &c.rounds};
      speedup.result.c = measure::analyze_pairs(measure::pair_rounds(base->rounds, c.rounds), settings);
      speedup.result.reliable = row.result.reliable;
      speedup.result.noise_reason = row.result.noise_reason;
      a.calibration.push_back(speedup);
    }
  }
}

// The limit arm's rows, and every scheduler row's loss account and comparison with the limit at its P: per round
// the row's time against the limit's throughput limit L per frame, and both arms' sampled work against
// the serial loop's (work inflation).
void scale_rows(const Measured& m, Analysis& a) {
  const measure::Settings settings = analysis_settings(m.o);
  auto inflation = [&](const measure::ArmRounds& sampled) -> std::optional<Inflation> {
    if (sampled.size() == 0 || m.serial_sampled.size() == 0) return std::nullopt;
    Inflation i{measure::analyze_pairs(measure::pair_rounds(sampled, m.serial_sampled), settings)};
    if (!i.valid()) return std::nullopt;
    return i;
  };
  std::vector<measure::ArmRounds> per_worker_limit, per_worker_wall;  // the limit's rounds over P, per limit row
  for (const Cell& c : m.cells) {
    if (c.role != ArmRole::kLimit) continue;
    LimitRow l;
    l.cell = &c;
    l.path_ms = median(c.path_ms);
    l.speedup = a.t1_ms / (l.path_ms / c.workers);
    measure::ArmRounds scaled = c.rounds, scaled_wall = c.limit_wall;
    for (double& t : scaled.time) t /= static_cast<double>(c.workers);
    for (double& t : scaled_wall.time) t /= static_cast<double>(c.workers);
    l.wall_speedup = a.t1_ms / (median(c.limit_wall_path_ms()) / c.workers);
    l.vs_serial.c = measure::analyze_pairs(measure::pair_rounds(scaled, m.serial_rounds), settings);
    l.inflation = inflation(c.sampled);
    l.copy_spread = c.frames_run ? c.limit_copy_spread_sum / static_cast<double>(c.frames_run) : 0;
    a.limits.push_back(l);
    per_worker_limit.push_back(std::move(scaled));
    per_worker_wall.push_back(std::move(scaled_wall));
  }
  for (Row& r : a.rows) {
    const Cell& c = *r.cell;
    Account& acc = r.account;
    acc.terms = make_account(c.account);
    acc.inflation = inflation(c.sampled);
    for (std::size_t i = 0; i < a.limits.size(); ++i) {
      const LimitRow& l = a.limits[i];
      if (l.cell->workers != c.workers) continue;
      ShownComparison vs;
      vs.c = measure::analyze_pairs(measure::pair_rounds(c.rounds, per_worker_limit[i]), settings);
      vs.reliable = r.vs_serial.reliable;
      vs.noise_reason = r.vs_serial.noise_reason;
      r.vs_limit = vs;
      vs.c = measure::analyze_pairs(measure::pair_rounds(c.rounds, per_worker_wall[i]), settings);
      r.vs_limit_wall = vs;
      const double work = acc.terms.share(Term::kWork);
      if (acc.inflation && l.inflation) {
        acc.split_by_limit = true;
        acc.work_at_limit = work * l.inflation->factor() / acc.inflation->factor();
        acc.inflation_beyond_limit = work - acc.work_at_limit;
      }
    }
  }
}

// "faster than queue-mutex (time -11.6 % [-15.0, -8.1])" and the like: one clause of the short answer.
std::string answer_clause(const ShownComparison& s, const std::string& other, double margin) {
  const measure::LogInterval& li = s.c.chosen();
  const std::string numbers = "time " + std::string(li.effect_pct() >= 0 ? "+" : "") + fixed(li.effect_pct(), 1) +
                              " % [" + fixed(100 * (li.ratio_low() - 1), 1) + ", " +
                              fixed(100 * (li.ratio_high() - 1), 1) + "]";
  std::string clause;
  switch (s.c.decision) {
    case measure::Decision::kFaster: clause = "FASTER than " + other + " (" + numbers + ")"; break;
    case measure::Decision::kSlower: clause = "SLOWER than " + other + " (" + numbers + ")"; break;
    case measure::Decision::kEquivalent:
      clause = "EQUIVALENT to " + other + " within +-" + fixed(100 * margin, 1) + " % (" + numbers + ")";
      break;
    case measure::Decision::kInconclusive:
      clause =
          "not decided against " + other + " (" + numbers +
          (std::isfinite(s.c.rounds_needed) ? "; about " + std::to_string(static_cast<long>(s.c.rounds_needed)) +
                                                  " rounds would decide, " + std::to_string(s.c.rounds) + " were run)"
                                            : "; the estimate sits on the margin: no number of rounds decides it)");
      break;
    case measure::Decision::kTooFewRounds: clause = "not compared with " + other + " (too few rounds)"; break;
  }
  if (!s.reliable) clause = "UNRELIABLE against " + other + " (" + s.noise_reason + ")";
  return clause;
}

// The clause of policies that got the same verdict against `other`: the verdict once, with the range of their
// estimates ("not decided against queue-mutex (time -3.3 ... -2.5 %; 329-1868 rounds would decide)").
std::string agreed_clause(const std::vector<const ShownComparison*>& cs, const std::string& other, double margin) {
  double lo = 1e300, hi = -1e300, need_lo = 1e300, need_hi = 0;
  for (const ShownComparison* c : cs) {
    lo = std::min(lo, c->c.chosen().effect_pct());
    hi = std::max(hi, c->c.chosen().effect_pct());
    need_lo = std::min(need_lo, c->c.rounds_needed);
    need_hi = std::max(need_hi, c->c.rounds_needed);
  }
  auto pct = [](double v) { return std::string(v >= 0 ? "+" : "") + fixed(v, 1); };
  const std::string range = "time " + pct(lo) + " ... " + pct(hi) + " %";
  const ShownComparison& first = *cs.front();
  if (!first.reliable) return "UNRELIABLE against " + other + " (" + first.noise_reason + ")";
  switch (first.c.decision) {
    case measure::Decision::kFaster: return "FASTER than " + other + " (" + range + ")";
    case measure::Decision::kSlower: return "SLOWER than " + other + " (" + range + ")";
    case measure::Decision::kEquivalent:
      return "EQUIVALENT to " + other + " within +-" + fixed(100 * margin, 1) + " % (" + range + ")";
    case measure::Decision::kInconclusive: {
      const bool finite = std::isfinite(need_lo) && std::isfinite(need_hi);
      return "not decided against " + other + " (" + range +
             (finite ? "; " + std::to_string(static_cast<long>(need_lo)) + "-" +
                           std::to_string(static_cast<long>(need_hi)) + " rounds would decide, " +
                           std::to_string(first.c.rounds) + " were run)"
                     : "; some sit on the margin: no number of rounds decides them)");
    }
    case measure::Decision::kTooFewRounds: return "not compared with " + other + " (too few rounds)";
  }
  return "";
}

// The rounds a comparison of the table has (every row's are alike: one per segment per pass).
std::size_t rows_rounds(const Analysis& a) { return a.rows.empty() ? 0 : a.rows.front().vs_serial.c.rounds; }

// The short answer: per P, each stealing policy against queue-mutex and against the best other scheduler (the
// fastest non-stealing one at that P by its ratio to the serial loop), one sentence each.
void short_answer(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  const measure::Settings settings = analysis_settings(o);
  std::vector<WorkerId> ps;
  for (const Row& r : a.rows) {
    if (std::find(ps.begin(), ps.end(), r.cell->workers) == ps.end()) ps.push_back(r.cell->workers);
  }
  std::vector<double> mdes, removed;
  for (const Row& r : a.rows) {
    if (r.vs_queue && r.vs_queue->c.adjusted.valid) removed.push_back(100 * r.vs_queue->c.variance_removed);
    if (r.cell->workers > m.cores) continue;
    if (r.vs_queue && r.vs_queue->c.chosen().valid) mdes.push_back(r.vs_queue->c.mde_pct);
  }
  a.median_mde_pct = median(mdes);
  a.median_variance_removed_pct = median(removed);
  for (WorkerId p : ps) {
    const Row* best = nullptr;
    for (const Row& r : a.rows) {
      if (r.cell->workers != p || r.cell->scheduler.rfind("stealing/", 0) == 0 || !r.vs_serial.c.chosen().valid)
        continue;
      if (!best || r.vs_serial.c.chosen().estimate < best->vs_serial.c.chosen().estimate) best = &r;
    }
    // Each stealing policy against queue-mutex and the best other scheduler; when every policy gets the same
    // verdicts, one sentence says so with the range of their estimates.
    struct Verdicts {
      const Row* row;
      std::optional<ShownComparison> best;
    };
    std::vector<Verdicts> policies;
    for (const Row& r : a.rows) {
      if (r.cell->workers != p || r.cell->scheduler.rfind("stealing/", 0) != 0) continue;
      Verdicts v{&r, std::nullopt};
      if (best && best->cell->scheduler != "queue-mutex") {
        ShownComparison vs_best;
        vs_best.c = measure::analyze_pairs(measure::pair_rounds(r.cell->rounds, best->cell->rounds), settings);
        vs_best.reliable = r.vs_serial.reliable && best->vs_serial.reliable;
        vs_best.noise_reason = !r.vs_serial.reliable ? r.vs_serial.noise_reason : best->vs_serial.noise_reason;
        v.best = vs_best;
      }
      policies.push_back(v);
    }
    const std::string at = "P = " + std::to_string(p) + (p > m.cores ? " (oversubscribed)" : "") + ": ";
    const std::string best_name = best ? "the best other scheduler, " + best->cell->scheduler : "";
    auto kind = [](const std::optional<ShownComparison>& c) {
      return !c ? std::string("-") : !c->reliable ? std::string("unreliable") : measure::to_string(c->c.decision);
    };
    bool agree = policies.size() > 1;
    for (const Verdicts& v : policies) {
      agree = agree && kind(v.row->vs_queue) == kind(policies.front().row->vs_queue) &&
              kind(v.best) == kind(policies.front().best) && v.row->vs_queue;
    }
    if (agree) {
      std::string names;
      for (std::size_t i = 0; i < policies.size(); ++i) {
        names += (i == 0                     ? ""
                  : i + 1 == policies.size() ? " and "
                                             : ", ") +
                 policies[i].row->cell->scheduler.substr(std::string("stealing/").size());
      }
      std::vector<const ShownComparison*> q, b;
      for (const Verdicts& v : policies) {
        q.push_back(&*v.row->vs_queue);
        if (v.best) b.push_back(&*v.best);
      }
      std::string sentence = at + "the " + std::to_string(policies.size()) + " stealing policies (" + names +
                             ") agree: each is " + agreed_clause(q, "queue-mutex", o.margin);
      if (!b.empty()) {
        sentence += ", and " + agreed_clause(b, best_name, o.margin);
      } else if (best) {
        sentence += " (queue-mutex is also the fastest other scheduler here)";
      }
      a.answer.push_back(sentence + ".");
      continue;
    }
    for (const Verdicts& v : policies) {
      const Row& r = *v.row;
      std::string sentence = at + r.cell->scheduler + " is ";
      sentence +=
          r.vs_queue ? answer_clause(*r.vs_queue, "queue-mutex", o.margin) : "not compared with queue-mutex (not run)";
      if (v.best) {
        sentence += ", and " + answer_clause(*v.best, best_name, o.margin);
      } else if (best) {
        sentence += " (queue-mutex is also the fastest other scheduler here)";
      }
      a.answer.push_back(sentence + ".");
    }
  }
  const std::size_t rounds = m.serial_rounds.size();
  const std::size_t per_comparison = rows_rounds(a);
  a.design_line =
      std::to_string(per_comparison) + " rounds per comparison (" + std::to_string(o.repeats) +
      " passes x segments of " + std::to_string(o.round_frames) + " frames; " + std::to_string(rounds) +
      " rounds in all, each the serial loop and every arm of one P once, in " + measure::to_string(o.order) +
      " order; " + instances_text(o) + "); verdicts on the per-round log-ratio (" + measure::to_string(o.estimator) +
      ", segments as blocks), Student-t 95 % interval" +
      (o.adjust ? " adjusted for the CPU speed probe (regression on the probe before each arm; it removed a "
                  "median " +
                      fixed(a.median_variance_removed_pct, 0) +
                      " % of the variance, raw intervals in "
                      "the JSON)"
                : " (raw)") +
      ", margin +-" + fixed(100 * o.margin, 1) + " %; this run finds a change of " + fixed(a.median_mde_pct, 1) +
      " % with 80 % power (median over the comparisons with queue-mutex at "
      "P <= " +
      std::to_string(m.cores) + ")";
}

// The stealing policy the scale sentences speak for: Fenced (the exactly-once default of the paper's handshake
// with its StoreLoad fences) when it ran, else the first stealing policy of the run.
const Row* reference_policy(const Analysis& a, WorkerId p) {
  const Row* first = nullptr;
  for (const Row& r : a.rows) {
    if (r.cell->workers != p || r.cell->scheduler.rfind("stealing/", 0) != 0) continue;
    if (r.cell->scheduler == "stealing/Fenced") return &r;
    if (!first) first = &r;
  }
  return first;
}

// The account's losses of a row, largest first: every term but work, and the inflation beyond the limit's.
std::vector<std::pair<double, std::string>> losses(const Row& r) {
  std::vector<std::pair<double, std::string>> out;
  for (std::size_t i = 0; i < kTerms; ++i) {
    const auto t = static_cast<Term>(i);
    if (t == Term::kWork) continue;
    out.emplace_back(r.account.terms.share(t), describe(t));
  }
  if (r.account.split_by_limit) out.emplace_back(r.account.inflation_beyond_limit, "inflation beyond the limit's");
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  return out;
}

// Per P, one sentence: the reference policy's limit-efficiency with its interval, its three largest losses as
// the account gives them, and against the ideal T1 / P how much the machine took (the limit's own loss) and how
// much the scheduler (everything between the limit and the scheduler), and which dominates.
void scale_answer(const Measured& m, Analysis& a) {
  for (const LimitRow& l : a.limits) {
    const WorkerId p = l.cell->workers;
    const Row* r = reference_policy(a, p);
    if (!r || !r->vs_limit || !r->vs_limit->c.chosen().valid) continue;
    const double eff = r->limit_efficiency();
    const double ideal = r->ideal_pct / 100;
    std::ostringstream s;
    s << "P = " << p << (p > m.cores ? " (oversubscribed)" : "") << ": " << r->cell->scheduler << " used "
      << fixed(100 * eff, 1) << " % [" << fixed(100 * r->limit_efficiency_low(), 1) << ", "
      << fixed(100 * r->limit_efficiency_high(), 1) << "] of the machine's limit (" << p
      << (p == 1 ? " serial loop on a worker thread ran " : " serial loops at once ran ") << fixed(l.speedup, 2)
      << "x the serial loop's frames)";
    const auto loss = losses(*r);
    s << "; its largest losses, as shares of P x T:";
    for (std::size_t i = 0; i < std::min<std::size_t>(3, loss.size()); ++i) {
      s << (i ? "," : "") << " " << fixed(100 * loss[i].first, 1) << " % " << loss[i].second;
    }
    if (!r->account.terms.closes()) {
      s << " (the account does not close: " << fixed(100 * r->account.terms.share(Term::kUnaccounted), 1)
        << " % unaccounted)";
    }
    const double machine = eff - ideal, scheduler = 1 - eff;
    s << ". Against the ideal T1 / " << std::min<WorkerId>(p, m.cores) << " it reached " << fixed(100 * ideal, 1)
      << " %: the machine took " << fixed(100 * machine, 1) << " % (the limit's own loss with " << p
      << (p == 1 ? " busy core" : " busy cores") << "), the scheduler " << fixed(100 * scheduler, 1) << " % -- the "
      << (std::fabs(machine) > std::fabs(scheduler) ? "machine's" : "scheduler's") << " loss dominates.";
    a.scale_answer.push_back(s.str());
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
      r.busy = sc::summarize_spread(frame_medians(c.busy_ratio, o.frames));  // median over passes, per frame
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

// The one-line summaries: spread of the passes, noise, interference, tessellation audit, the LLVM child,
// and the noise warning (empty when every verdict is reliable).
void summary_lines(const Measured& m, Analysis& a) {
  const Options& o = m.o;
  a.machine = cpu_model() + ", " + std::to_string(m.cores) + " hardware threads";
  a.path_line = path_line(m);
  std::vector<double> cell_spreads;
  for (const Row& r : a.rows) cell_spreads.push_back(r.spread_pct);
  std::ostringstream spread;
  spread << "spread of single passes (max/min - 1, context only: the verdicts rest on the paired rounds): serial loop "
         << fixed(100 * a.serial_spread, 1) << " %; schedulers: median " << fixed(median(cell_spreads), 1) << " %, max "
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
  for (const std::string& note : a.notes) noise << "; " << note << " (context: not while the pairs ran)";
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
    warning << "WARNING: " << a.unreliable << " of " << a.verdicts << " verdicts are marked unreliable. Reasons:\n";
    for (const auto& w : a.noise_warnings) warning << "  - " << w << "\n";
    std::size_t cell_flags = 0;
    for (const Row& r : a.rows) {
      for (const ShownComparison* x : {&r.vs_serial, r.vs_queue ? &*r.vs_queue : nullptr}) {
        if (!x || x->reliable || (!a.noise_warnings.empty() && x->noise_reason == a.noise_warnings.front())) continue;
        if (cell_flags++ < 5) {
          warning << "  - " << r.cell->scheduler << " P=" << r.cell->workers << ": " << x->noise_reason << "\n";
        }
      }
    }
    if (cell_flags > 5) warning << "  - ... and " << cell_flags - 5 << " more comparisons\n";
    warning << "Re-run those comparisons when the machine is not shared with other work.\n";
    a.warning = warning.str();
  }
  for (int f = 0; f < o.frames; ++f) {
    a.capped_total += m.wl.serial_capped[f];
    a.capped_max = std::max(a.capped_max, m.wl.serial_capped[f]);
  }
  if (a.serial_inconsistencies > 0) a.problems = true;
  // One line that says what "audit ok" covers, and what it found.
  std::ostringstream audit;
  audit << "tessellation audit (every surface of every frame, every run: trimmed pieces tiled exactly, "
           "(u, v) area = trim-loop area): "
        << a.serial_inconsistencies << " inconsistencies in the serial loop; surfaces held at the "
        << m.wl.settings.max_steps << "-step cap (deviation may exceed " << o.tolerance
        << " px there): " << a.capped_total << " surface-frames, at most " << a.capped_max << " per frame";
  a.tessellation_audit = audit.str();
  a.remade = remade_line(o, m.wl);
  std::ostringstream child;  // how openmp-static-steal ran, and the proof that static_steal was in effect
  for (const Cell& c : m.cells) {
    if (c.child) {
      child << c.scheduler << " P=" << c.workers << ": child process " << shown_path(sc::llvm_openmp_child_path())
            << " (clang++-14, libomp; per-item code compiled by clang), " << c.child->ready_line()
            << "; steals = chunks run off their static owner\n";
    }
  }
  a.child_note = child.str();
}

}  // namespace

Analysis analyze(const Measured& m) {
  Analysis a;
  for (int f = 0; f < m.o.frames; ++f) a.serial_inconsistencies += m.wl.serial_inconsistencies[f];
  judge_rows(m, a);
  scale_rows(m, a);
  short_answer(m, a);
  scale_answer(m, a);
  cost_spreads(m, a);
  summary_lines(m, a);
  return a;
}

}  // namespace frontsteal::main_job
