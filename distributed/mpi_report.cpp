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
           {"progress_calls", s.progress_calls}});
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
  js["noise_warning"] = noise_warning(results);
  js["work_ns"] = run.work_ns;  // with scene and items: what frontsteal-mpi-simulate --validate needs to re-run it
  js["skew"] = run.skew;
  return js;
}

void report_results(const Options& o, const RunSummary& run, const std::vector<SchedulerResult>& results) {
  print_classic_table(run, results);
  const report::Table t = intervals_table(results);
  const std::string warning = noise_warning(results);
  std::printf(
      "\nmedians with 95 %% bootstrap confidence intervals (frames: per-frame times; steals and owner "
      "ops: per rank); %s\n%s",
      run.progress.describe().c_str(), t.terminal().c_str());
  std::printf("%s\n", warning.empty() ? "noise monitor: every scheduler's window was quiet" : warning.c_str());
  std::printf("every frame audited: each item exactly once, triangles equal to the serial loop's\n");
  if (!o.json.empty()) {
    report::write_atomically(o.json, run_json(run, results).dump(2) + "\n");
    std::fprintf(stderr, "%s: wrote %s\n", kProgram.data(), o.json.c_str());
  }
  if (!o.markdown.empty()) {
    std::string md = "# frontsteal-mpi: " + std::to_string(run.ranks) + " ranks, " + run.scene + " (" +
                     std::to_string(run.items) + " items), " + std::to_string(run.frames) +
                     " frames (measured, commit " + FRONTSTEAL_GIT_COMMIT + ")\n\n" + run.progress.describe() + "\n\n" +
                     t.markdown() + "\n" +
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
