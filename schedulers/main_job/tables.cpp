// tables.cpp — the main job's shown table and data table (tables.hpp).
#include "schedulers/main_job/tables.hpp"

#include <string>
#include <vector>

namespace frontsteal::main_job {

namespace {

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// "0.981 [0.952, 1.012]": L / T_P with its interval, or "-" without a limit arm.
std::string limit_efficiency_text(const Row& r) {
  if (!r.vs_limit || !r.vs_limit->c.chosen().valid) return "-";
  return fixed(r.limit_efficiency(), 3) + " [" + fixed(r.limit_efficiency_low(), 3) + ", " +
         fixed(r.limit_efficiency_high(), 3) + "]";
}

}  // namespace

// The table as the terminal and frontsteal.md show it: the serial loop first, then every scheduler and P,
// then the cells that could not run. Existing columns first, in their old order; the added ones (cpu, off-cpu,
// the two comparisons) after lock waits, audit last.
report::Table shown_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"},
                   {"scheduler", "scheduler", text},
                   {"frames_per_s", "frames/s"},
                   {"speedup", "speed-up"},
                   {"ideal_pct", "% of ideal"},
                   {"utilization_pct", "utilization"},
                   {"imbalance_mean", "imbalance"},
                   {"steals", "steals (failed)"},
                   {"lock_waits", "lock waits"},
                   {"cpu_pct", "cpu"},
                   {"off_cpu_pct", "off-cpu"},
                   {"ratio_vs_serial", "T_P/T1 [95% CI]", text},
                   {"verdict_vs_serial", "vs serial", text},
                   {"ratio_vs_queue", "T_P/T_queue [95% CI]", text},
                   {"verdict_vs_queue", "vs queue-mutex", text},
                   {"limit_efficiency", "limit-eff [95% CI]", text},
                   {"audit", "audit", text}});
  t.add_row({1, "serial loop (T1)", fixed(1000.0 * m.o.frames / a.t1_ms, 2), "1.00", "100.0", "-", "-", "-", "-", "-",
             "-", "reference", "-", "-", "-", "-", "-"});
  WorkerId shown_limit = 0;
  for (const Row& r : a.rows) {
    // Each P's rows start with its limit arm (P serial loops at once): the reference of the limit-efficiency.
    for (const LimitRow& l : a.limits) {
      if (l.cell->workers != r.cell->workers || l.cell->workers == shown_limit) continue;
      shown_limit = l.cell->workers;
      const double fps = 1000.0 * m.o.frames * l.speedup / a.t1_ms;
      t.add_row({l.cell->workers, std::string(kLimitName) + " (" + std::to_string(l.cell->workers) + " serial loops)",
                 fixed(fps, 2), fixed(l.speedup, 2),
                 fixed(100 * l.speedup / std::min<double>(l.cell->workers, m.cores), 1), "-", "-", "-", "-", "-", "-",
                 l.vs_serial.interval_text(), l.vs_serial.verdict_text(), "-", "-", "reference",
                 l.cell->failed() ? "FAILED" : "ok"});
    }
    const Cell& c = *r.cell;
    const std::uint64_t failed = c.totals.steal_attempts - c.totals.steals_succeeded;
    t.add_row({c.workers, c.scheduler, fixed(r.fps, 2), fixed(r.speedup, 2), fixed(r.ideal_pct, 1),
               fixed(r.utilization, 1) + "%", fixed(r.imbalance_mean, 3),
               std::to_string(c.totals.steals_succeeded) + " (" + std::to_string(failed) + ")", c.totals.lock_waits,
               fixed(r.cpu_pct, 1) + "%", fixed(r.off_cpu_pct, 1) + "%", r.vs_serial.interval_text(),
               r.vs_serial.verdict_text(), r.vs_queue ? r.vs_queue->interval_text() : "-",
               r.vs_queue ? r.vs_queue->verdict_text() : (c.scheduler == "queue-mutex" ? "reference" : "-"),
               limit_efficiency_text(r), c.failed() ? "FAILED" : "ok"});
  }
  for (const Cell& c : m.not_available) {
    t.add_row({c.workers, c.scheduler, "not available: " + c.unavailable, "-", "-", "-", "-", "-", "-", "-", "-", "-",
               "-", "-", "-", "-", "-"});
  }
  return t;
}

report::Table account_table(const Analysis& a) {
  const bool text = false;
  std::vector<report::Column> columns{{"workers", "P"},
                                      {"scheduler", "scheduler", text},
                                      {"limit_efficiency", "limit-eff [95% CI]", text},
                                      {"work_at_limit", "work at the limit's speed"},
                                      {"inflation_beyond_limit", "inflation beyond the limit's"}};
  for (std::size_t i = 1; i < kTerms; ++i) {
    const auto term = static_cast<Term>(i);
    columns.push_back({name(term), name(term)});
  }
  columns.push_back({"closes", "closes", text});
  report::Table t(std::move(columns));
  auto pct = [](double share) { return fixed(100 * share, 1); };
  for (const Row& r : a.rows) {
    const Account& acc = r.account;
    std::vector<report::Cell> row{r.cell->workers, r.cell->scheduler, limit_efficiency_text(r)};
    if (acc.split_by_limit) {
      row.emplace_back(pct(acc.work_at_limit));
      row.emplace_back(pct(acc.inflation_beyond_limit));
    } else {
      row.emplace_back(pct(acc.terms.share(Term::kWork)));
      row.emplace_back("-");
    }
    for (std::size_t i = 1; i < kTerms; ++i) row.emplace_back(pct(acc.terms.share(static_cast<Term>(i))));
    row.emplace_back(acc.terms.closes() ? "yes" : "NO");
    t.add_row(std::move(row));
  }
  return t;
}

// The data (frontsteal.csv, and each row of frontsteal.json's results[]): full precision, the serial loop first.
report::Table data_table(const Measured& m, const Analysis& a) {
  const bool text = false;
  report::Table t({{"workers", "P"},
                   {"scheduler", "scheduler", text},
                   {"path_ms", "path (ms)"},
                   {"frames_per_s", "frames/s"},
                   {"speedup", "speed-up"},
                   {"ideal_pct", "% of ideal"},
                   {"utilization_pct", "utilization (%)"},
                   {"imbalance_mean", "imbalance"},
                   {"imbalance_max", "max imbalance"},
                   {"steals", "steals"},
                   {"steal_attempts", "steal attempts"},
                   {"lock_waits", "lock waits"},
                   {"lock_wait_ms", "lock wait (ms)"},
                   {"setup_ms", "set-up (ms)"},
                   {"audit_failures", "audit failures"},
                   {"triangle_mismatches", "triangle mismatches"},
                   {"tessellation_inconsistencies", "tessellation inconsistencies"},
                   {"cpu_pct", "cpu (%)"},
                   {"off_cpu_pct", "off-cpu (%)"},
                   {"path_spread_pct", "spread (%)"},
                   {"ratio_vs_serial", "T_P/T1"},
                   {"ratio_vs_serial_ci_low", "T_P/T1 low"},
                   {"ratio_vs_serial_ci_high", "T_P/T1 high"},
                   {"verdict_vs_serial", "vs serial", text},
                   {"effect_vs_serial_pct", "effect vs serial (%)"},
                   {"ratio_vs_queue", "T_P/T_queue"},
                   {"ratio_vs_queue_ci_low", "T_P/T_queue low"},
                   {"ratio_vs_queue_ci_high", "T_P/T_queue high"},
                   {"verdict_vs_queue", "vs queue-mutex", text},
                   {"effect_vs_queue_pct", "effect vs queue-mutex (%)"},
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
    const measure::LogInterval& li = c->c.chosen();
    const std::string verdict = c->reliable ? measure::to_string(c->c.decision) : "unreliable";
    if (!li.valid) {  // too few rounds: no numbers, only the verdict
      row.insert(row.end(), {none, none, none, verdict, none});
      return;
    }
    row.insert(row.end(), {num(li.ratio()), num(li.ratio_low()), num(li.ratio_high()), verdict, num(li.effect_pct())});
  };
  for (const Row& r : a.rows) {
    const Cell& c = *r.cell;
    std::vector<report::Cell> row{c.workers,
                                  c.scheduler,
                                  num(r.path_ms),
                                  num(r.fps),
                                  num(r.speedup),
                                  num(r.ideal_pct),
                                  num(r.utilization),
                                  num(r.imbalance_mean),
                                  num(c.imbalance_max),
                                  c.totals.steals_succeeded,
                                  c.totals.steal_attempts,
                                  c.totals.lock_waits,
                                  num(c.totals.lock_wait_ns / 1e6),
                                  num(c.setup_ms),
                                  c.audit_failures,
                                  c.triangle_mismatches,
                                  c.tessellation_inconsistencies,
                                  num(r.cpu_pct),
                                  num(r.off_cpu_pct),
                                  num(r.spread_pct)};
    comparison(row, &r.vs_serial);
    comparison(row, r.vs_queue ? &*r.vs_queue : nullptr);
    row.emplace_back(r.vs_serial.reliable && (!r.vs_queue || r.vs_queue->reliable));
    t.add_row(std::move(row));
  }
  return t;
}

}  // namespace frontsteal::main_job
