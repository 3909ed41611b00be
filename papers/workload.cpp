// workload.cpp — measured runs and trace recording (workload.hpp).
#include "papers/workload.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "core/execution_counter.hpp"
#include "measure/cpu_speed_probe.hpp"
#include "measure/heap_offset.hpp"
#include "schedulers/registry.hpp"

namespace frontsteal::papers {

using Clock = std::chrono::steady_clock;

namespace {

tess::PathSceneOptions scene_options(const WorkloadOptions& o) {
  const auto kind = tess::camera_path_named(o.path);
  if (!kind) throw std::invalid_argument("unknown camera path '" + o.path + "'");
  tess::PathSceneOptions so{.scene = o.scene,
                            .data_dir = o.data_dir,
                            .path = *kind,
                            .frames = o.frames,
                            .width = o.width,
                            .height = o.height,
                            .settings = {}};
  so.settings.pixel_tolerance = o.tolerance_px;
  return so;
}

}  // namespace

PathWorkload::PathWorkload(const WorkloadOptions& options)
    : options_(options), scene_(tess::make_path_scene(scene_options(options))), frames_(scene_, 1) {
  // The hints of the main job: patch centres, and the cost estimate of the path's first (overview) view.
  hints_.centres = scene_.centres();
  hints_.costs = scene_.estimated_costs(0);
}

CostTrace record_cost_trace(PathWorkload& wl, int passes, const std::string& machine, const std::string& commit,
                            bool median_of_passes) {
  CostTrace t;
  t.scene = wl.options().scene;
  if (wl.options().path != "orbit-then-zoom") t.path = wl.options().path;  // the default keeps its old spelling
  t.width = wl.options().width;
  t.height = wl.options().height;
  t.tolerance_px = wl.options().tolerance_px;
  t.passes = passes;
  t.machine = machine;
  t.commit = commit;
  t.centres = wl.hints().centres;
  t.estimates = wl.hints().costs;
  const ItemId n = wl.surfaces();
  // Clock overhead: the time of an empty timed region, subtracted from every sample.
  double clock_ns = 0;
  {
    std::vector<double> v;
    for (int i = 0; i < 1001; ++i) {
      const auto a = Clock::now();
      const auto b = Clock::now();
      v.push_back(std::chrono::duration<double, std::nano>(b - a).count());
    }
    clock_ns = median(v);
  }
  std::vector<std::vector<std::vector<double>>> samples(wl.frames(), std::vector<std::vector<double>>(n));
  for (int pass = -1; pass < passes; ++pass) {  // pass -1 warms caches and buffers, not recorded
    for (int f = 0; f < wl.frames(); ++f) {
      for (ItemId id = 0; id < n; ++id) {
        const auto a = Clock::now();
        wl.tessellate(f, id, 0);
        const auto b = Clock::now();
        if (pass >= 0) {
          samples[f][id].push_back(std::max(0.0, std::chrono::duration<double, std::nano>(b - a).count() - clock_ns));
        }
      }
    }
  }
  t.cost_ns.assign(wl.frames(), std::vector<double>(n));
  for (int f = 0; f < wl.frames(); ++f) {
    for (ItemId id = 0; id < n; ++id) {
      const auto& v = samples[f][id];
      t.cost_ns[f][id] =
          median_of_passes ? median(v) : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    }
  }
  return t;
}

std::vector<MeasuredRun> measure_schedulers(PathWorkload& wl, const MeasureOptions& o, double* serial_ms,
                                            MeasurementNoise* noise) {
  const ItemId n = wl.surfaces();
  WorkerId max_p = 1;
  for (WorkerId p : o.threads) max_p = std::max(max_p, p);
  wl.prepare_workers(max_p);

  std::vector<std::uint64_t> reference;  // per frame: the serial loop's triangles
  for (int f = 0; f < wl.frames(); ++f) {
    for (ItemId id = 0; id < n; ++id) wl.tessellate(f, id, 0);
    reference.push_back(wl.frame_triangles());
  }

  struct Cell {
    MeasuredRun run;
    const sched::SchedulerInfo* info = nullptr;
    measure::HeapOffset heap_offset;  // declared before the instance: outlives it
    std::unique_ptr<sched::Scheduler> instance;
    double busy = 0, cpu = 0, available = 0, imbalance_sum = 0;
    std::uint64_t frames = 0;
  };
  // Every round runs fresh instances, each at a random heap offset (measure/heap_offset.hpp) and warmed up on
  // frame 0 untimed: two instances of the same code differ by a few per cent for as long as they live, so with
  // one instance per run that difference would be a constant no interval over rounds includes; renewed every
  // round (a round is a whole path here), it is part of each round's noise and the rounds stay independent.
  std::uint64_t draws = 0;
  auto renew = [&](Cell& c) {
    c.instance.reset();
    c.heap_offset.redraw(o.seed, draws++);
    c.instance = c.info->make({.workers = c.run.workers, .items = n, .seed = o.seed}, wl.hints());
    auto warm = [&](ItemId id, WorkerId w) { wl.tessellate(0, id, w); };
    c.instance->run_frame(warm);
  };
  std::vector<Cell> cells;
  for (WorkerId p : o.threads) {
    for (const auto& name : o.schedulers) {
      Cell c;
      c.info = sched::find_scheduler(name);
      if (!c.info) throw std::invalid_argument("unknown scheduler '" + name + "'");
      c.run.scheduler = name;
      c.run.workers = p;
      cells.push_back(std::move(c));
    }
  }
  ExecutionCounter runs(n);
  std::vector<double> serial_path, serial_probe;
  std::vector<noise::PassUsage> serial_passes;
  measure::ArmRounds serial_rounds;
  const noise::ProcSample measure_start = noise::sample_now();
  auto run_serial = [&](int r, double probe) {
    const noise::PassMeter meter;
    const auto t0 = Clock::now();
    for (int f = 0; f < wl.frames(); ++f) {
      for (ItemId id = 0; id < n; ++id) wl.tessellate(f, id, 0);
    }
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    serial_passes.push_back(meter.stop());  // before the push_backs below can allocate
    serial_path.push_back(ms);
    serial_probe.push_back(probe);
    serial_rounds.add(static_cast<std::size_t>(r), ms, probe, 0);
  };
  auto run_cell = [&](Cell& c, int r, double probe) {
    double total = 0;
    const noise::ProcSample before = noise::sample_now();
    for (int f = 0; f < wl.frames(); ++f) {
      auto item = [&](ItemId id, WorkerId w) {
        runs.record(id);
        wl.tessellate(f, id, w);
      };
      const auto t0 = Clock::now();
      const FrameStats& st = c.instance->run_frame(item);
      total += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      const WorkerFrameStats tot = st.totals();
      c.busy += static_cast<double>(tot.busy_ns);
      c.cpu += static_cast<double>(tot.cpu_ns);
      c.available += static_cast<double>(st.wall_ns) * static_cast<double>(st.workers.size());
      c.imbalance_sum += st.imbalance();
      ++c.frames;
      c.run.steals += tot.steals_succeeded;
      c.run.lock_waits += tot.lock_waits;
      const ExecutionAudit audit = runs.audit_and_reset();
      if (!audit.exactly_once() || wl.frame_triangles() != reference[f]) {
        throw std::runtime_error(c.run.scheduler + " P=" + std::to_string(c.run.workers) + " frame " +
                                 std::to_string(f) +
                                 ": audit failed (a surface not run exactly once, or the "
                                 "triangle count differs from the serial loop's)");
      }
    }
    c.run.usage += noise::usage_between(before, noise::sample_now());
    c.run.path_ms.push_back(total);
    c.run.rounds.add(static_cast<std::size_t>(r), total, probe, 0);
    if (o.progress) {
      o.progress("repeat " + std::to_string(r + 1) + "/" + std::to_string(o.repeats) +
                 " P=" + std::to_string(c.run.workers) + " " + c.run.scheduler + ": " +
                 std::to_string(total).substr(0, 6) + " ms");
    }
  };
  for (int r = 0; r < o.repeats; ++r) {
    for (Cell& c : cells) renew(c);
    // Arm 0 is the serial loop, arm k the k-th cell; before each, a pause for library runtimes to settle, then
    // the probe (the covariate of measure/paired_analysis.hpp), before the arm so that it cannot depend on it.
    for (std::size_t arm : measure::round_order(cells.size() + 1, o.seed, static_cast<std::size_t>(r), o.order)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      const double probe = noise::probe_ns_per_million_steps();
      if (arm == 0) {
        run_serial(r, probe);
      } else {
        run_cell(cells[arm - 1], r, probe);
      }
    }
  }
  if (noise) {
    noise->during = noise::usage_between(measure_start, noise::sample_now());
    noise->serial_path_ms = serial_path;
    noise->serial_probe = serial_probe;
    noise->serial_passes = serial_passes;
    noise->serial_rounds = serial_rounds;
  }
  std::vector<MeasuredRun> out;
  for (Cell& c : cells) {
    c.run.median_path_ms = median(c.run.path_ms);
    c.run.frames_per_s = 1000.0 * wl.frames() / c.run.median_path_ms;
    c.run.utilization_pct = c.available > 0 ? 100.0 * c.busy / c.available : 0;
    c.run.cpu_pct = c.available > 0 ? 100.0 * c.cpu / c.available : 0;
    c.run.imbalance_mean = c.frames ? c.imbalance_sum / static_cast<double>(c.frames) : 0;
    c.run.busy_ms_per_path = c.busy / 1e6 / static_cast<double>(o.repeats);
    out.push_back(std::move(c.run));
  }
  if (serial_ms) *serial_ms = median(serial_path);
  return out;
}

}  // namespace frontsteal::papers
