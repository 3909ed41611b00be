// mpi_report.cpp — frontsteal-mpi's tables, markdown and JSON (mpi_report.hpp).
#include "distributed/mpi_report.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

#include "distributed/mpi_plots.hpp"
#include "measure/paired_comparison.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::mpi {
namespace {

double total_of(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }
double max_of(const std::vector<double>& v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }
double mean_latency_us(const RankStats& s) { return s.steals > 0 ? 1e6 * s.steal_latency_s / s.steals : 0.0; }
// One-sided operations per successful one-sided steal (0 for schedulers that steal by message).
double operations_per_steal(const RankStats& s) { return s.steals > 0 ? s.steal_operations / s.steals : 0.0; }

// The first table, as it has always been printed (its columns are what earlier results files hold).
void print_classic_table(const RunSummary& run, const std::vector<SchedulerResult>& results) {
  std::printf("\nfrontsteal-mpi: %d ranks, %s (%u items), %d frames, commit %s (measured)\n", run.ranks,
              run.scene.c_str(), run.items, run.frames, FRONTSTEAL_GIT_COMMIT);
  std::printf("%-8s %9s %11s | %4s %8s %9s %7s %7s %12s %11s %12s\n", "sched", "frames/s", "median ms", "rank",
              "busy s", "items", "steals", "tries", "lat mean us", "bytes", "owner ns/op");
  std::printf("%-8s %9s %11s | %4s %8s %9s %7s %7s %12s %11s %12s\n", "", "", "(max ms)", "", "", "", "", "", "", "",
              "(median)");
  for (const SchedulerResult& r : results) {
    for (std::size_t k = 0; k < r.ranks.size(); ++k) {
      const RankStats& s = r.ranks[k];
      std::string rate, ms;
      if (k == 0) {
        rate = std::to_string(static_cast<double>(r.frame_s.size()) / total_of(r.frame_s)).substr(0, 8);
        ms = std::to_string(1000 * median(r.frame_s)).substr(0, 8);
      } else if (k == 1) {
        ms = "(" + std::to_string(1000 * max_of(r.frame_s)).substr(0, 7) + ")";
      }
      std::printf("%-8s %9s %11s | %4zu %8.3f %9.0f %7.0f %7.0f %12.1f %11.0f %12.1f\n", k == 0 ? r.name.c_str() : "",
                  rate.c_str(), ms.c_str(), k, s.busy_s, s.items, s.steals, s.steal_attempts, mean_latency_us(s),
                  s.bytes, s.owner_overhead_median_ns);
    }
  }
}

report::Json interval(double lo, double hi) { return report::Json::array({lo, hi}); }

}  // namespace

report::Table intervals_table(const std::vector<SchedulerResult>& results) {
  using report::Cell;
  report::Table t({{"scheduler", "scheduler", false},
                   {"rank", "rank"},
                   {"frame_ms_median", "frame ms median"},
                   {"frame_ms_ci_low", "95% CI low"},
                   {"frame_ms_ci_high", "95% CI high"},
                   {"frames_per_s_from_median", "frames/s (1/median)"},
                   {"steals", "steals"},
                   {"steal_latency_median_us", "steal us median"},
                   {"steal_latency_ci_low_us", "95% CI low"},
                   {"steal_latency_ci_high_us", "95% CI high"},
                   {"owner_ns_median", "owner ns/op median"},
                   {"owner_ns_ci_low", "95% CI low"},
                   {"owner_ns_ci_high", "95% CI high"},
                   {"progress_calls", "progress calls"},
                   {"operations_per_steal", "one-sided ops/steal"},
                   {"noise", "noise", false}});
  for (const SchedulerResult& r : results) {
    std::vector<double> ms(r.frame_s.size());
    std::transform(r.frame_s.begin(), r.frame_s.end(), ms.begin(), [](double s) { return 1000 * s; });
    const stats::Interval f = stats::bootstrap_median_ci(ms);
    for (std::size_t k = 0; k < r.ranks.size(); ++k) {
      const RankStats& s = r.ranks[k];
      const bool first = k == 0;
      const bool stole = s.steals > 0;
      t.add_row(
          {first ? Cell(r.name) : Cell(""), Cell(static_cast<int>(k)), first ? Cell::fixed(f.median, 2) : Cell::empty(),
           first ? Cell::fixed(f.low, 2) : Cell::empty(), first ? Cell::fixed(f.high, 2) : Cell::empty(),
           first && f.median > 0 ? Cell::fixed(1000 / f.median, 2) : Cell::empty(),
           Cell(static_cast<std::int64_t>(s.steals)), stole ? Cell::fixed(s.steal_latency_median_us, 1) : Cell::empty(),
           stole ? Cell::fixed(s.steal_latency_ci_low_us, 1) : Cell::empty(),
           stole ? Cell::fixed(s.steal_latency_ci_high_us, 1) : Cell::empty(),
           Cell::fixed(s.owner_overhead_median_ns, 1), Cell::fixed(s.owner_overhead_ci_low_ns, 1),
           Cell::fixed(s.owner_overhead_ci_high_ns, 1), Cell(static_cast<std::int64_t>(s.progress_calls)),
           stole && s.steal_operations > 0 ? Cell::fixed(operations_per_steal(s), 1) : Cell::empty(),
           first ? Cell(r.noise.busy ? "NOISY" : "quiet") : Cell("")});
    }
  }
  return t;
}

std::string noise_warning(const std::vector<SchedulerResult>& results) {
  std::string w;
  for (const SchedulerResult& r : results) {
    if (r.noise.busy) w += (w.empty() ? "" : "; ") + r.name + ": " + r.noise.reason;
  }
  return w.empty() ? w : "WARNING: the machine was not quiet (noise monitor) — " + w + ". Treat these rates as noisy.";
}

report::Json run_json(const RunSummary& run, const std::vector<SchedulerResult>& results) {
  // The common header, then the keys in the order readers of older files expect, then the later keys.
  report::Json js = report::document(kProgram, 1, "measured", FRONTSTEAL_GIT_COMMIT);
  js["measured"] = true;
  js["ranks"] = run.ranks;
  js["scene"] = run.scene;
  js["items"] = run.items;
  js["frames"] = run.frames;
  js["schedulers"] = report::Json::array();
  for (const SchedulerResult& r : results) {
    std::vector<double> ms(r.frame_s.size());
    std::transform(r.frame_s.begin(), r.frame_s.end(), ms.begin(), [](double s) { return 1000 * s; });
    const stats::Interval f = stats::bootstrap_median_ci(ms);
    report::Json sj;
    sj["name"] = r.name;
    sj["frames_per_s"] = static_cast<double>(r.frame_s.size()) / total_of(r.frame_s);
    sj["median_frame_ms"] = 1000 * median(r.frame_s);
    sj["max_frame_ms"] = 1000 * max_of(r.frame_s);
    sj["audited_frames"] = r.audited_frames;
    sj["per_rank"] = report::Json::array();
    for (std::size_t k = 0; k < r.ranks.size(); ++k) {
      const RankStats& s = r.ranks[k];
      sj["per_rank"].push_back(
          {{"rank", k},
           {"busy_s", s.busy_s},
           {"items", s.items},
           {"steals", s.steals},
           {"steal_attempts", s.steal_attempts},
           {"steal_latency_mean_us", mean_latency_us(s)},
           {"steal_latency_max_us", 1e6 * s.steal_latency_max_s},
           {"bytes_moved", s.bytes},
           {"owner_overhead_ns_per_op", s.owner_ops > 0 ? 1e9 * s.owner_overhead_s / s.owner_ops : 0.0},
           {"owner_overhead_median_ns", s.owner_overhead_median_ns},
           {"t4_wait_s", s.t4_wait_s},
           {"t4_polls", s.t4_spins},
           {"idle_s", s.idle_s},
           {"owner_ops", s.owner_ops},
           {"requests_served", s.requests_served},
           {"steal_latency_median_us", s.steal_latency_median_us},
           {"steal_latency_median_ci95_us", interval(s.steal_latency_ci_low_us, s.steal_latency_ci_high_us)},
           {"owner_overhead_median_ci95_ns", interval(s.owner_overhead_ci_low_ns, s.owner_overhead_ci_high_ns)},
           {"progress_calls", s.progress_calls},
           {"local_steals", s.local_steals},
           {"one_sided_operations_per_steal", operations_per_steal(s)}});
    }
    sj["median_frame_ms_ci95"] = interval(f.low, f.high);
    sj["frames_per_s_from_median"] = f.median > 0 ? 1000 / f.median : 0.0;
    sj["frames_per_s_from_median_ci95"] = interval(f.high > 0 ? 1000 / f.high : 0.0, f.low > 0 ? 1000 / f.low : 0.0);
    sj["noise"] = {{"busy", r.noise.busy},
                   {"reason", r.noise.reason},
                   {"other_share_max", r.noise.other_share_max},
                   {"steal_share_max", r.noise.steal_share_max},
                   {"load1", r.noise.load1}};
    js["schedulers"].push_back(sj);
  }
  js["owner_progress"] = run.progress.describe();
  js["owner_progress_us"] = run.progress.every_us;
  js["progress_thread_sleep_us"] = run.progress.thread_sleep_us;
  js["noise_warning"] = noise_warning(results);
  js["work_ns"] = run.work_ns;  // with scene and items: what frontsteal-mpi-simulate --validate needs to re-run it
  js["skew"] = run.skew;
  js["threads"] = run.threads;  // hier's workers per rank and refill size, for the same
  js["chunk_us"] = run.chunk_us;
  js["lifelines"] = run.lifelines;
  js["batch_claims"] = run.batch_claims;
  js["thief_reads"] = run.thief_views ? "view" : "words";
  return js;
}

namespace {

const char* role_name(ArmRole r) {
  switch (r) {
    case ArmRole::kScheduler: return "scheduler";
    case ArmRole::kReference: return "reference";
    case ArmRole::kTwin: return "A/A twin";
    case ArmRole::kPlanted: return "planted";
  }
  return "?";
}

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// "+9.8 % [8.0, 11.6]": the change in time with its interval.
std::string change_text(const measure::PairedResult& r) {
  const measure::LogInterval& li = r.chosen();
  if (!li.valid) return "no interval";
  const double e = 100 * (li.ratio() - 1), lo = 100 * (li.ratio_low() - 1), hi = 100 * (li.ratio_high() - 1);
  return (e >= 0 ? "+" : "") + fixed(e, 1) + " % [" + fixed(lo, 1) + ", " + fixed(hi, 1) + "]";
}

}  // namespace

report::Table paired_table(const PairedReport& paired) {
  using report::Cell;
  report::Table t({{"arm", "arm", false},
                   {"role", "role", false},
                   {"rounds", "rounds"},
                   {"time_ratio", "time / " + paired.reference},
                   {"time_ratio_ci_low", "95% CI low"},
                   {"time_ratio_ci_high", "95% CI high"},
                   {"speedup", "speed-up"},
                   {"speedup_ci_low", "95% CI low"},
                   {"speedup_ci_high", "95% CI high"},
                   {"verdict", "verdict (margin)", false},
                   {"differs", "differs"},
                   {"variance_removed_by_probe", "probe: variance removed"}});
  for (const ArmComparison& c : paired.comparisons) {
    const measure::LogInterval& li = c.result.chosen();
    const bool v = li.valid;
    t.add_row({Cell(c.label), Cell(role_name(c.role)), Cell(static_cast<std::uint64_t>(c.result.rounds)),
               v ? Cell::fixed(li.ratio(), 3) : Cell::empty(), v ? Cell::fixed(li.ratio_low(), 3) : Cell::empty(),
               v ? Cell::fixed(li.ratio_high(), 3) : Cell::empty(), v ? Cell::fixed(1 / li.ratio(), 3) : Cell::empty(),
               v ? Cell::fixed(1 / li.ratio_high(), 3) : Cell::empty(),
               v ? Cell::fixed(1 / li.ratio_low(), 3) : Cell::empty(),
               Cell(std::string(measure::to_string(c.result.decision)) + " (+-" + fixed(paired.margin_pct, 1) + " %)"),
               Cell(c.result.differs),
               c.result.uses_adjusted ? Cell::fixed(c.result.variance_removed, 2) : Cell::empty()});
  }
  return t;
}

std::string paired_answer(const PairedReport& paired) {
  std::string out = "paired rounds: " + std::to_string(paired.rounds) + " rounds of " +
                    std::to_string(paired.frames_per_pass) +
                    " frames per arm, arms in a random order each round, times by rank 0's clock (measured)\n";
  for (const ArmComparison& c : paired.comparisons) {
    if (c.role != ArmRole::kScheduler) continue;
    const measure::LogInterval& li = c.result.chosen();
    if (!li.valid) {
      out += "  " + c.label + ": " + measure::to_string(c.result.decision) + " against " + paired.reference + "\n";
      continue;
    }
    out += "  " + c.label + ": " + fixed(1 / li.ratio(), 2) + "x the speed of " + paired.reference + " [" +
           fixed(1 / li.ratio_high(), 2) + ", " + fixed(1 / li.ratio_low(), 2) + "], " +
           measure::to_string(c.result.decision) + "\n";
  }
  out += "the method in this run: ";
  for (const ArmComparison& c : paired.comparisons) {
    if (c.role == ArmRole::kTwin)
      out += "A/A twin " + std::string(measure::to_string(c.result.decision)) + " (" + change_text(c.result) + "); ";
    if (c.role == ArmRole::kPlanted)
      out += "planted +" + fixed(c.planted_pct, 1) + " % " + measure::to_string(c.result.decision) + " (" +
             change_text(c.result) + (paired.method.planted_size_held ? ", its size inside the interval" : "") + ")";
  }
  out += "\n";
  if (!paired.method.passed()) {
    out += "METHOD CHECK FAILED: ";
    out += paired.method.twin_false_alarm ? "the A/A twin was called different; " : "";
    out += paired.method.planted_found ? "" : "the planted slowdown was not found; ";
    out += "treat the verdicts above as unproven (more rounds, a quieter machine)\n";
  } else if (!paired.method.twin_equivalent) {
    out += "the A/A twin was not called equivalent: this run's noise needs more rounds for equivalence verdicts\n";
  }
  return out;
}

void report_results(const Options& o, const RunSummary& run, const std::vector<SchedulerResult>& results,
                    const PairedReport* paired) {
  if (paired) std::printf("%s", paired_answer(*paired).c_str());
  print_classic_table(run, results);
  const report::Table t = intervals_table(results);
  const std::string warning = noise_warning(results);
  std::printf(
      "\nmedians with 95 %% bootstrap confidence intervals (frames: per-frame times; steals and owner "
      "ops: per rank); %s\n%s",
      run.progress.describe().c_str(), t.terminal().c_str());
  std::printf("%s\n", warning.empty() ? "noise monitor: every scheduler's window was quiet" : warning.c_str());
  std::printf("every frame audited: each item exactly once, triangles equal to the serial loop's\n");
  if (paired)
    std::printf("\npaired against %s (95 %% intervals, Huber estimate, probe-adjusted where it helps)\n%s",
                paired->reference.c_str(), paired_table(*paired).terminal().c_str());
  if (!o.json.empty()) {
    report::Json js = run_json(run, results);
    if (paired) {
      js["paired"] = {{"reference", paired->reference},
                      {"rounds", paired->rounds},
                      {"frames_per_pass", paired->frames_per_pass},
                      {"margin_pct", paired->margin_pct},
                      {"arms", paired_table(*paired).json()},
                      {"method_passed", paired->method.passed()},
                      {"twin_equivalent", paired->method.twin_equivalent},
                      {"planted_found", paired->method.planted_found},
                      {"planted_size_held", paired->method.planted_size_held}};
    }
    report::write_atomically(o.json, js.dump(2) + "\n");
    std::fprintf(stderr, "%s: wrote %s\n", kProgram.data(), o.json.c_str());
  }
  if (!o.markdown.empty()) {
    std::string md = "# frontsteal-mpi: " + std::to_string(run.ranks) + " ranks, " + run.scene + " (" +
                     std::to_string(run.items) + " items), " + std::to_string(run.frames) +
                     " frames (measured, commit " + FRONTSTEAL_GIT_COMMIT + ")\n\n" +
                     (paired ? "```\n" + paired_answer(*paired) + "```\n\n" + paired_table(*paired).markdown() + "\n"
                             : std::string()) +
                     run.progress.describe() + "\n\n" + t.markdown() + "\n" +
                     (warning.empty() ? "Noise monitor: every scheduler's window was quiet.\n" : warning + "\n");
    report::write_atomically(o.markdown, md);
    std::fprintf(stderr, "%s: wrote %s\n", kProgram.data(), o.markdown.c_str());
  }
  if (!o.plots.empty()) {
    write_run_plots(o.plots,
                    std::to_string(run.ranks) + " ranks, " + run.scene + ", " + std::to_string(run.frames) +
                        " frames, commit " + FRONTSTEAL_GIT_COMMIT + "; " + run.progress.describe(),
                    results);
    std::fprintf(stderr, "%s: wrote the plots to %s\n", kProgram.data(), o.plots.c_str());
  }
}

}  // namespace frontsteal::mpi
