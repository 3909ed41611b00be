// frontsteal-mpi-simulate — SIMULATED efficiency of rma stealing, request-based stealing, the central counter
// and static round robin at 16, 64 and 256 ranks (and 2, 4 to set beside frontsteal-mpi's measurements),
// from latencies that frontsteal-mpi --calibrate --json measured (rma_simulator.hpp: the model and what it
// leaves out). Prints a table per calibration; --json and --markdown write the same, labelled SIMULATED.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "distributed/rma_simulator.hpp"
#include "distributed/simulator_validation.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"

namespace sim = frontsteal::mpi::sim;
namespace report = frontsteal::report;

namespace {

// --validate: each measured run re-run in the model with the first calibration's latencies; ratios to static
// round robin compared (simulator_validation.hpp). Returns the exit status.
int run_validation(const std::string& calibration, const std::vector<std::string>& runs, const std::string& json,
                   const std::string& markdown) {
  constexpr double kWithin = 0.10;
  const sim::Latencies lat = sim::latencies_from_calibration(calibration);
  report::Table t({{"run", "measured run", false},
                   {"ranks", "ranks"},
                   {"scheduler", "scheduler", false},
                   {"measured_ms", "measured ms/frame"},
                   {"simulated_ms", "SIMULATED ms/frame"},
                   {"measured_ratio", "measured / static"},
                   {"simulated_ratio", "SIMULATED / static"},
                   {"ratio_error_percent", "ratio error %"},
                   {"within", "within 10 %", false}});
  std::string notes;
  int outside = 0, rows = 0;
  bool audit_ok = true;
  for (const std::string& path : runs) {
    const sim::MeasuredRun run = sim::read_measured_run(path);
    if (!run.assumed.empty()) notes += path + ": assumed " + run.assumed + "\n";
    for (const sim::ValidationRow& r : sim::validate(run, lat)) {
      const bool within = std::abs(r.ratio_error) <= kWithin;
      if (r.scheduler != "static") {
        ++rows;
        if (!within) ++outside;
      }
      audit_ok = audit_ok && r.exactly_once;
      t.add_row({path, run.ranks, r.scheduler, report::Cell::fixed(r.measured_ms, 2),
                 report::Cell::fixed(r.simulated_ms, 2), report::Cell::fixed(r.measured_ratio, 3),
                 report::Cell::fixed(r.simulated_ratio, 3), report::Cell::fixed(100 * r.ratio_error, 1),
                 r.scheduler == "static" ? "reference"
                 : within                ? "yes"
                                         : "NO"});
    }
  }
  const std::string answer = std::to_string(rows - outside) + " of " + std::to_string(rows) +
                             " scheduler ratios within 10 % of the measured ones";
  const std::string title = "SIMULATED against MEASURED: " + answer + " (latencies: " + lat.source +
                            "; each scheduler's frame time relative to static round robin in the same run)\n";
  std::printf("%s%s%s", title.c_str(), notes.c_str(), t.terminal().c_str());
  if (!json.empty()) {
    report::Json doc = report::document("frontsteal-mpi-simulate", 1, "simulated", FRONTSTEAL_GIT_COMMIT);
    doc["contents"] = "validation";
    doc["latencies"] = sim::latencies_json(lat);
    doc["within_percent"] = 100 * kWithin;
    doc["rows"] = t.json();
    report::write_atomically(json, doc.dump(2) + "\n");
  }
  if (!markdown.empty()) report::write_atomically(markdown, "# " + title + "\n" + notes + "\n" + t.markdown());
  return audit_ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> calibrations;
  std::vector<int> ranks{2, 4, 16, 64, 256};
  sim::Workload w;
  std::string json, markdown, defect = "none";
  report::CommandLine cli(
      "frontsteal-mpi-simulate",
      "usage: frontsteal-mpi-simulate --calibration FILE[,FILE...] [options]\n\nSIMULATED: "
      "predicts each scheduler's efficiency (work / (ranks x threads x time)) with a discrete-event model "
      "driven by measured latencies (frontsteal-mpi --calibrate --json).",
      "\nExit status: 0; 1 the model's exactly-once audit failed; 2 bad command line.");
  cli.app()
      .add_option("--calibration", calibrations, "calibration JSON files (comma list)")
      ->delimiter(',')
      ->required();
  cli.app()
      .add_option("--ranks", ranks, "rank counts (comma list)")
      ->delimiter(',')
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  cli.option("--items", w.items, "items per frame")->check(CLI::Range(16u, 10000000u));
  std::string shape = "skewed";
  cli.option("--shape", shape,
             "cost shape (synthetic_cost.hpp): skewed (frontsteal-mpi synthetic:N) | cascade (cascade:N, cost "
             "concentrated in space)")
      ->check(CLI::IsMember({"skewed", "cascade"}));
  cli.option("--work-ns", w.light_ns, "a light item's cost (cascade: the mean item's), ns")
      ->check(CLI::Range(0.0, 1e9));
  cli.option("--skew", w.skew, "the moving heavy fifth costs K x")->check(CLI::Range(1u, 10000u));
  cli.option("--frames", w.frames, "frames (lists carry over)")->check(CLI::Range(1, 1000));
  std::vector<int> threads{1};
  cli.app()
      .add_option("--threads", threads,
                  "workers per rank (comma list): hier's threads; static and static-space share a rank's items among "
                  "them perfectly; rma, request and central run one rank per worker")
      ->delimiter(',')
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  std::vector<std::string> schedulers{"rma", "request", "central", "static", "static-space", "hier", "hier-seeded"};
  cli.app()
      .add_option("--schedulers", schedulers, "schedulers to model (comma list)")
      ->delimiter(',')
      ->check(CLI::IsMember({"rma", "request", "central", "static", "static-space", "hier", "hier-seeded"}))
      ->capture_default_str();
  cli.option("--chunk-us", w.chunk_us, "hier: a refill from the rank list is about this much work (frontsteal-mpi's)")
      ->check(CLI::Range(0.001, 1e6));
  std::string lifelines = "on";
  cli.option("--lifelines", lifelines,
             "hier: on = a dry rank registers at its lifelines and waits to be invited, and the count's zero is "
             "broadcast (rma_simulator.hpp's LIFELINES); off = rounds of random victims with back-off (as "
             "frontsteal-mpi --lifelines)")
      ->check(CLI::IsMember({"on", "off"}));
  std::string batch_claims = "on";
  cli.option("--batch-claims", batch_claims,
             "hier: on = a refill makes one owner claim per run of consecutive ids of its chunk; off = one per item "
             "(as frontsteal-mpi --batch-claims)")
      ->check(CLI::IsMember({"on", "off"}));
  bool limits = false;
  cli.flag("--limits", limits,
           "also print what no scheduler of whole items beats at each ranks x threads: the bound max(work / "
           "workers, largest item), greedy in id order and longest first, at no cost (about 10 s per 2,000,000 "
           "items x 5 frames and worker count)");
  double local_steal_ns = -1;
  cli.option("--local-steal-ns", local_steal_ns,
             "hier: a sibling steal inside a rank, ns (ASSUMED; default 1000: frontsteal-mpi --calibrate does not "
             "measure it)")
      ->check(CLI::Range(0.0, 1e9));
  double progress_every_us = 50;
  cli.option("--progress-every-us", progress_every_us,
             "over a transport that needs target progress: the owner's "
             "progress call / request poll interval (frontsteal-mpi --owner-progress; its auto is 50)")
      ->check(CLI::Range(0.0, 1e6));
  cli.option("--json", json, "also write the results as JSON");
  std::string plots;
  cli.option("--plots", plots, "also plot efficiency against ranks into this directory (PNG through gnuplot)");
  cli.option("--markdown", markdown, "also write the results as markdown");
  cli.option("--plant-defect", defect, "negative control: none | skip-reread (rma thieves keep [mid, end))")
      ->check(CLI::IsMember({"none", "skip-reread"}));
  std::vector<std::string> validate;
  cli.app()
      .add_option("--validate", validate,
                  "measured runs (frontsteal-mpi --json, synthetic shapes, one rank per core) to re-run in the model "
                  "with the first calibration: each scheduler's frame time relative to static round robin, "
                  "SIMULATED against measured (comma list); the other workload options are then taken from the files")
      ->delimiter(',')
      ->check(CLI::ExistingFile);
  cli.parse(argc, argv);
  if (!validate.empty()) {
    try {
      return run_validation(calibrations.front(), validate, json, markdown);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "frontsteal-mpi-simulate: %s\n", e.what());
      return 1;
    }
  }
  w.lifelines = lifelines == "on";
  w.batch_claims = batch_claims == "on";
  w.shape = shape == "cascade" ? frontsteal::mpi::CostShape::kCascade : frontsteal::mpi::CostShape::kSkewed;
  const std::string shape_text =
      shape == "cascade" ? "cost cascade, mean " + report::fixed_text(w.light_ns, 0) + " ns"
                         : "light " + report::fixed_text(w.light_ns, 0) + " ns, heavy fifth x" + std::to_string(w.skew);
  try {
    report::Table t({{"latencies", "latencies", false},
                     {"scheduler", "scheduler", false},
                     {"ranks", "ranks"},
                     {"threads", "threads"},
                     {"efficiency", "efficiency (SIMULATED)"},
                     {"efficiency_carried", "after frame 1"},
                     {"frame_ms", "ms/frame"},
                     {"steals", "remote steals"},
                     {"local_steals", "local steals"},
                     {"mean_steal_us", "mean steal us"},
                     {"attempts", "remote attempts"},
                     {"remote_ops", "remote ops"},
                     {"bottleneck", "largest loss (hier)", false},
                     {"exactly_once", "audit", false}});
    report::Json doc = report::document("frontsteal-mpi-simulate", 1, "simulated", FRONTSTEAL_GIT_COMMIT);
    doc["simulated"] = true;
    doc["workload"] = {
        {"shape", shape},     {"items", w.items},       {"light_ns", w.light_ns},   {"skew", w.skew},
        {"frames", w.frames}, {"chunk_us", w.chunk_us}, {"lifelines", w.lifelines}, {"batch_claims", w.batch_claims}};
    report::Json losses = report::Json::array();
    doc["latencies"] = report::Json::array();
    bool audit_ok = true;
    for (const std::string& path : calibrations) {
      sim::Latencies lat = sim::latencies_from_calibration(path);
      lat.progress_every = progress_every_us * 1e3;
      if (local_steal_ns >= 0) lat.local_steal = local_steal_ns;
      doc["latencies"].push_back(sim::latencies_json(lat));
      const std::string label = lat.needs_target_progress ? "tcp" : "shm";
      for (sim::Scheduler s :
           {sim::Scheduler::kRma, sim::Scheduler::kRequest, sim::Scheduler::kCentral, sim::Scheduler::kStatic,
            sim::Scheduler::kStaticSpace, sim::Scheduler::kHier, sim::Scheduler::kHierSeeded}) {
        if (std::find(schedulers.begin(), schedulers.end(), sim::to_string(s)) == schedulers.end()) continue;
        for (int threads_per_rank : threads) {
          for (int p : ranks) {
            sim::Workload wt = w;
            wt.threads = threads_per_rank;
            std::fprintf(stderr, "frontsteal-mpi-simulate: %s %s %d x %d ...\n", label.c_str(), sim::to_string(s), p,
                         threads_per_rank);
            const sim::Result r = sim::simulate(
                s, p, wt, lat, 1, defect == "skip-reread" ? sim::Defect::kSkipReread : sim::Defect::kNone);
            if (!r.exactly_once) {
              std::fprintf(stderr, "frontsteal-mpi-simulate: MODEL AUDIT FAILED: %s, %d ranks, %s: %s\n",
                           sim::to_string(s), p, label.c_str(), r.audit_failure.c_str());
              audit_ok = false;
            }
            std::string largest = "-";
            if (s == sim::Scheduler::kHier || s == sim::Scheduler::kHierSeeded) {
              const auto [part, share] = r.loss.bottleneck();
              largest = std::string(part) + " " + report::fixed_text(100 * share, 1) + " %";
              const double all = r.loss.total();
              losses.push_back({{"latencies", label},
                                {"scheduler", sim::to_string(s)},
                                {"ranks", p},
                                {"threads", threads_per_rank},
                                {"work", r.loss.work / all},
                                {"claims", r.loss.claims / all},
                                {"local_steals", r.loss.local_steals / all},
                                {"remote_steals", r.loss.remote_steals / all},
                                {"idle", r.loss.idle / all},
                                {"tail", r.loss.tail / all},
                                {"barrier", r.loss.barrier / all},
                                {"bottleneck", part}});
            }
            t.add_row({label, sim::to_string(s), p, threads_per_rank, report::Cell::fixed(r.efficiency, 3),
                       report::Cell::fixed(r.efficiency_carried, 3), report::Cell::fixed(r.time_ns / w.frames / 1e6, 3),
                       r.steals, r.local_steals, report::Cell::fixed(r.mean_steal_ns / 1e3, 1), r.steal_attempts,
                       r.remote_operations, largest, r.exactly_once ? "passed" : "FAILED"});
          }
        }
      }
    }
    doc["rows"] = t.json();
    doc["hier_loss_shares"] = losses;
    std::string limits_text, limits_markdown;
    if (limits) {  // the workload's own ceiling (rma_simulator.hpp, WorkloadLimits)
      report::Table lt({{"workers", "ranks x threads", false},
                        {"largest_item_us", "largest item us"},
                        {"bound", "bound"},
                        {"greedy", "greedy, id order"},
                        {"lpt", "longest first"}});
      std::vector<int> done;
      for (int threads_per_rank : threads) {
        for (int p : ranks) {
          const int workers = p * threads_per_rank;
          if (std::find(done.begin(), done.end(), workers) != done.end()) continue;
          done.push_back(workers);
          std::fprintf(stderr, "frontsteal-mpi-simulate: the workload's limits at %d workers ...\n", workers);
          const sim::WorkloadLimits l = sim::workload_limits(w, workers);
          lt.add_row({std::to_string(p) + " x " + std::to_string(threads_per_rank),
                      report::Cell::fixed(l.max_item_ns / 1e3, 1), report::Cell::fixed(l.bound, 3),
                      report::Cell::fixed(l.greedy, 3), report::Cell::fixed(l.lpt, 3)});
        }
      }
      doc["limits"] = lt.json();
      const std::string heading =
          "What no scheduler of whole items beats (efficiency at no cost, SIMULATED from the costs):";
      limits_text = "\n" + heading + "\n" + lt.terminal();
      limits_markdown = "\n\n" + heading + "\n\n" + lt.markdown();
    }  // each part of the workers' time / the whole (rma_simulator.hpp)
    std::string latencies_text;
    for (const report::Json& l : doc["latencies"]) latencies_text += "  " + l.dump() + "\n";
    const std::string title = "SIMULATED (a discrete-event model, not a measurement): " + std::to_string(w.items) +
                              " items/frame, " + shape_text + ", " + std::to_string(w.frames) + " frames" +
                              (w.lifelines ? ", lifelines" : ", no lifelines") +
                              (w.batch_claims ? ", batch claims" : ", one claim per item") + "\nlatencies used (ns):\n";
    std::printf("%s%s%s%s", title.c_str(), latencies_text.c_str(), t.terminal().c_str(), limits_text.c_str());
    if (!json.empty()) report::write_atomically(json, doc.dump(2) + "\n");
    if (!plots.empty()) {
      bool tcp = false;
      for (const report::Json& l : doc["latencies"]) tcp = tcp || l.value("needs_target_progress", false);
      sim::write_efficiency_plot(
          plots, doc["rows"],
          std::to_string(w.items) + " items/frame, " + shape_text + "; shm = shared memory" +
              (tcp ? ", tcp = over TCP (owner calls into MPI every " + report::fixed_text(progress_every_us, 0) + " us)"
                   : std::string()));
      if (!losses.empty()) {
        sim::write_loss_plot(plots, losses, std::to_string(w.items) + " items/frame, " + shape_text);
      }
    }
    if (!markdown.empty()) {
      report::write_atomically(markdown,
                               "# " + title + "\n```\n" + latencies_text + "```\n\n" + t.markdown() + limits_markdown);
    }
    return audit_ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "frontsteal-mpi-simulate: %s\n", e.what());
    return 1;
  }
}
