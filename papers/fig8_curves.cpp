// fig8_curves.cpp — Fig. 8 measured and simulated (fig8_curves.hpp).
#include "papers/fig8_curves.hpp"

#include <filesystem>
#include <iostream>

#include "papers/fig8_report.hpp"
#include "papers/paper_numbers.hpp"

namespace frontsteal::papers {

SceneCurves curves_for_trace(const CostTrace& t, const Overheads& ov, PaperRun& run) {
  const Options& o = run.options();
  SceneCurves c;
  c.scene = t.scene;
  c.surfaces = t.surfaces();
  c.serial_fps = 1e9 * static_cast<double>(t.frames()) / t.path_cost_ns();
  c.sim_ps = simulated_ps(o.max_p);
  for (WorkerId p : c.sim_ps) {
    PerModel<SimulatedRun> row;
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      row[m] = simulate_model(t, ov, kFig8Models[m].model, p, o.seed);
      require_audit(row[m], std::string(kFig8Models[m].label) + " P=" + std::to_string(p));
    }
    c.sim.push_back(row);
    if (p % 8 == 0 || p == c.sim_ps.back()) run.say("  simulated " + t.scene + " up to P=" + std::to_string(p));
  }
  return c;
}

namespace {

// One stand-in: the four schedulers measured at P = 1 ... cores, then the trace simulated.
SceneCurves measure_scene(PaperRun& run, const std::string& scene) {
  const Options& o = run.options();
  PathWorkload wl = run.load(scene);
  MeasureOptions mo{
      .schedulers = {}, .threads = measured_ps(), .repeats = o.repeats, .seed = o.seed, .progress = run.sink()};
  for (const auto& m : kFig8Models) mo.schedulers.push_back(m.scheduler);
  run.say("fig8 " + scene + ": measuring 4 schedulers at P = 1 ... " + std::to_string(hardware_cores()));
  MeasurementNoise sampled;
  const std::vector<MeasuredRun> meas = measure_schedulers(wl, mo, nullptr, &sampled);
  const MeasuredNoise noise(sampled);
  const CostTrace t = run.record_trace(wl);
  const Overheads& ov = run.overheads();
  run.say("fig8 " + scene + ": simulating P = 1 ... " + std::to_string(o.max_p));
  SceneCurves c = curves_for_trace(t, ov, run);
  c.noise_line = noise.line();
  c.noise = noise.json();
  for (WorkerId p : mo.threads) {
    PerModel<double> fps{}, sim{}, busy{}, cpu{};
    PerModel<std::vector<double>> paths;
    PerModel<const MeasuredRun*> runs{};
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      for (const MeasuredRun& r : meas) {
        if (r.workers == p && r.scheduler == kFig8Models[m].scheduler) runs[m] = &r;
      }
      fps[m] = runs[m]->frames_per_s;
      busy[m] = runs[m]->busy_ms_per_path;
      cpu[m] = runs[m]->cpu_pct;
      paths[m] = runs[m]->path_ms;
      sim[m] = simulate_model(t, ov, kFig8Models[m].model, p, o.seed).frames_per_s;
    }
    c.meas_ps.push_back(p);
    c.meas_fps.push_back(fps);
    c.sim_at_meas_fps.push_back(sim);
    c.meas_busy_ms.push_back(busy);
    c.meas_cpu_pct.push_back(cpu);
    c.meas_path_ms.push_back(paths);
    c.meas_verdicts.push_back(
        {noise.judge(*runs[kQueueModel], *runs[kStaticModel]), noise.judge(*runs[kStealingModel], *runs[kQueueModel])});
  }
  return c;
}

}  // namespace

int run_fig8(PaperRun& run) {
  run.overheads();  // calibrated first, as before the split: the microbenchmarks run on a machine at rest
  std::vector<std::string> scenes = run.options().scenes;
  if (scenes.empty()) {
    for (int n : kPaperFig8Surfaces) scenes.push_back("plant:" + std::to_string(n));
  }
  std::vector<SceneCurves> all;
  for (const std::string& scene : scenes) all.push_back(measure_scene(run, scene));
  write_fig8(all, run, "fig8");
  return 0;
}

int run_simulate(PaperRun& run) {
  const Options& o = run.options();
  const std::string file =
      o.trace.empty() ? (std::filesystem::path(o.out) / ("trace-" + short_name(o.scene) + ".txt")).string() : o.trace;
  CostTrace t;
  try {
    t = read_cost_trace(file);
  } catch (const TraceError& e) {
    std::cerr << kPaperProgram << ": " << e.what() << '\n';
    return 2;
  }
  run.say("simulate: " + file + ": " + t.scene + ", " + std::to_string(t.surfaces()) + " surfaces, " +
          std::to_string(t.frames()) + " frames");
  std::vector<SceneCurves> all{curves_for_trace(t, run.overheads(), run)};
  write_fig8(all, run, "simulate-" + short_name(t.scene));
  return 0;
}

}  // namespace frontsteal::papers
