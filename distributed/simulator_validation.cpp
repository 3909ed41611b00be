// simulator_validation.cpp — the simulator against measured runs (simulator_validation.hpp).
#include "distributed/simulator_validation.hpp"

#include <stdexcept>

#include "distributed/mpi_options.hpp"
#include "distributed/synthetic_cost.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::mpi::sim {
namespace {

bool scheduler_named(const std::string& name, Scheduler& out) {
  for (Scheduler s : {Scheduler::kRma, Scheduler::kRequest, Scheduler::kCentral, Scheduler::kStatic,
                      Scheduler::kStaticSpace, Scheduler::kHier, Scheduler::kHierSeeded}) {
    if (name == to_string(s)) {
      out = s;
      return true;
    }
  }
  return false;
}

}  // namespace

MeasuredRun read_measured_run(const std::string& path) {
  const report::Json doc = report::read_document(path, "measured run");
  if (doc.value("program", "") != "frontsteal-mpi" || !doc.value("measured", false) || !doc.contains("schedulers")) {
    throw std::runtime_error(path + ": not a measured frontsteal-mpi run (frontsteal-mpi --json)");
  }
  MeasuredRun run;
  run.path = path;
  run.scene = doc.value("scene", "");
  run.ranks = doc.value("ranks", 0);
  const SyntheticScene scene = parse_synthetic_scene(run.scene);
  if (!scene.synthetic) {
    throw std::runtime_error(path + ": scene '" + run.scene +
                             "' is not a synthetic shape (synthetic:N, cascade:N); the model prices only those");
  }
  run.workload.shape = scene.shape;
  run.workload.items = doc.value("items", 0u);
  run.workload.frames = doc.value("frames", 0);
  if (run.ranks < 2 || run.workload.items == 0 || run.workload.frames < 1) {
    throw std::runtime_error(path + ": needs ranks >= 2, items and frames");
  }
  const Options defaults;
  if (doc.contains("work_ns")) {
    run.workload.light_ns = doc["work_ns"].get<double>();
  } else {
    run.workload.light_ns = defaults.work_ns;
    run.assumed += "work_ns " + std::to_string(defaults.work_ns) + " (frontsteal-mpi's default) ";
  }
  if (doc.contains("skew")) {
    run.workload.skew = doc["skew"].get<std::uint32_t>();
  } else {
    run.workload.skew = defaults.skew;
    run.assumed += "skew " + std::to_string(defaults.skew) + " (frontsteal-mpi's default) ";
  }
  run.workload.threads = doc.value("threads", defaults.threads);
  run.workload.chunk_us = doc.value("chunk_us", defaults.chunk_us);
  run.workload.lifelines = doc.value("lifelines", false);        // runs recorded before lifelines had none
  run.workload.batch_claims = doc.value("batch_claims", false);  // runs recorded before batch claims had none
  for (const report::Json& s : doc["schedulers"]) {
    run.schedulers.push_back({s.value("name", ""), s.value("median_frame_ms", 0.0)});
  }
  return run;
}

std::vector<ValidationRow> validate(const MeasuredRun& run, const Latencies& lat) {
  double measured_static = 0;
  for (const MeasuredScheduler& m : run.schedulers) {
    if (m.name == "static") measured_static = m.median_frame_ms;
  }
  if (measured_static <= 0) {
    throw std::runtime_error(run.path + ": no static (round robin) row to relate the other schedulers to");
  }
  Workload flat = run.workload;  // every scheduler but hier ran one thread per rank
  flat.threads = 1;
  const Result reference = simulate(Scheduler::kStatic, run.ranks, flat, lat);
  const double simulated_static = reference.time_ns / run.workload.frames / 1e6;
  std::vector<ValidationRow> rows;
  for (const MeasuredScheduler& m : run.schedulers) {
    Scheduler s{};
    if (!scheduler_named(m.name, s) || m.median_frame_ms <= 0) continue;
    const Result r = s == Scheduler::kStatic                                ? reference
                     : s == Scheduler::kHier || s == Scheduler::kHierSeeded ? simulate(s, run.ranks, run.workload, lat)
                                                                            : simulate(s, run.ranks, flat, lat);
    ValidationRow row;
    row.scheduler = m.name;
    row.measured_ms = m.median_frame_ms;
    row.simulated_ms = r.time_ns / run.workload.frames / 1e6;
    row.measured_ratio = m.median_frame_ms / measured_static;
    row.simulated_ratio = row.simulated_ms / simulated_static;
    row.ratio_error = row.simulated_ratio / row.measured_ratio - 1;
    row.exactly_once = r.exactly_once;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace frontsteal::mpi::sim
