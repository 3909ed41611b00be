// main_job_run.cpp — the main job's measurement (main_job_run.hpp): set-up of every cell, the serial loop,
// the in-process and the child paths, the interleaved rounds and the noise monitor's windows.
#include "schedulers/main_job_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <thread>
#include <utility>

#include "reporting/table.hpp"
#include "schedulers/cpu_speed_probe.hpp"
#include "schedulers/round_robin_spread.hpp"

namespace frontsteal::main_job {

namespace {

namespace report = frontsteal::report;

// The worker id this thread is pinned as under --pin (-1: not pinned). Pinning happens on a thread's first
// item of a frame rather than inside each scheduler, so it reaches the threads of oneTBB and OpenMP too,
// which we do not create.
thread_local int t_pinned_as = -1;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

// What the child must reproduce of the main job's workload.
sc::ChildWorkload child_workload(const Options& o) {
  sc::ChildWorkload cw;
  cw.scene = o.scene;
  cw.frames = o.frames;
  cw.path = ts::name(o.path);
  cw.tolerance = o.tolerance;
  cw.width = o.width;
  cw.height = o.height;
  cw.grain = o.grain;
  cw.plant_defect = o.planted_defect == ts::PlantedDefect::drop_ear               ? "drop-ear"
                    : o.planted_defect == ts::PlantedDefect::bridge_to_first_copy ? "wave1-bridge"
                                                                                  : "";
  cw.pin = o.pin;
  return cw;
}

}  // namespace

std::size_t progress_steps(const Options& o) {
  return 1 + static_cast<std::size_t>(std::max(o.repeats, 1)) * (1 + o.threads.size() * o.schedulers.size());
}

Measurement::Measurement(Options& o, Workload& wl, FrameTessellator& tess)
    : o_(o), wl_(wl), tess_(tess), runs_(static_cast<ItemId>(wl.model.surfaces.size())) {
  for (WorkerId p : o.threads) {
    for (const auto& name : o.schedulers) {
      Cell c;
      c.scheduler = name;
      c.workers = p;
      cells_.push_back(std::move(c));
    }
  }
}

int Measurement::co_runner_cpu() const {
  return o_.interference && o_.interference->pinned ? pinning_.cpu_of(0) : -1;
}

void Measurement::pin_as(WorkerId w) const {
  if (o_.pin && t_pinned_as != static_cast<int>(w)) {
    pinning_.pin_this_thread(w);
    t_pinned_as = static_cast<int>(w);
  }
}

// The caller of oneTBB and OpenMP is their worker 0: under --pin it is pinned by its first item, and given
// back every CPU after each path so the next scheduler's threads are not born confined to one core.
void Measurement::unpin_caller() const {
  if (!o_.pin) return;
  pinning_.unpin_this_thread();
  t_pinned_as = -1;
}

// openmp-static-steal: a child process per P, started here and kept (it warms up itself).
bool Measurement::start_child(Cell& c) {
  c.unavailable = sc::llvm_openmp_unavailable_reason();
  if (c.unavailable.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      c.child = std::make_unique<sc::LlvmOpenMpChild>(c.workers, static_cast<ItemId>(wl_.model.surfaces.size()),
                                                      child_workload(o_));
    } catch (const std::exception& e) {
      c.unavailable = e.what();
    }
    c.setup_ms = ms_since(t0);
  }
  if (!c.unavailable.empty()) {
    std::cerr << kProgram << ": " << c.scheduler << " P=" << c.workers << " not available: " << c.unavailable << '\n';
  }
  return c.unavailable.empty();
}

bool Measurement::start_cells(const sc::WorkloadHints& hints) {
  const auto n = static_cast<ItemId>(wl_.model.surfaces.size());
  for (Cell& c : cells_) {
    if (c.scheduler == sc::kLlvmOpenMpName) {
      start_child(c);
      continue;
    }
    const sc::SchedulerInfo* info = sc::find_scheduler(c.scheduler);
    sc::SchedulerConfig config{.workers = c.workers, .items = n, .grain = o_.grain, .seed = o_.seed};
    const auto t0 = std::chrono::steady_clock::now();
    try {
      c.instance = info->make(config, hints);
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": cannot start " << c.scheduler << " with P=" << c.workers << ": " << e.what() << '\n';
      return false;
    }
    c.setup_ms = ms_since(t0);
    auto warm = [&](ItemId id, WorkerId w) {
      pin_as(w);
      tess_.run(0, id, w);
    };
    c.instance->run_frame(warm);
    unpin_caller();
  }
  for (Cell& c : cells_) {
    if (!c.unavailable.empty()) not_available_.push_back(std::move(c));
  }
  std::erase_if(cells_, [](const Cell& c) { return !c.unavailable.empty() || (!c.instance && !c.child); });
  return true;
}

bool Measurement::start_interference() {
  if (!o_.interference) return true;
  try {
    co_runner_ = fi::CoRunner::start({.duty = o_.interference->duty, .period_us = 10'000,
                                      .cpu = o_.interference->pinned ? pinning_.cpu_of(0) : -1});
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": cannot start the interference co-runner: " << e.what() << '\n';
    return false;
  }
  if (!o_.quiet) {
    std::fprintf(stderr, "frontsteal: interference on: co-runner pid %d, %s\n", static_cast<int>(co_runner_.pid()),
                 o_.interference->describe().c_str());
  }
  return true;
}

// The serial reference (T1): a plain loop on this thread, the co-runner paused.
void Measurement::run_serial_path() {
  const auto n = static_cast<ItemId>(wl_.model.surfaces.size());
  std::vector<double> per_frame;
  double total = 0;
  if (o_.pin) pinning_.pin_this_thread(0);
  co_runner_.pause();  // T1 is the undisturbed reference (no-op without --interference)
  const double probe_before = nz::probe_ns_per_million_steps();  // the pass's thread (its core, too, with --pin)
  const nz::ProcSample before = sample();
  const nz::PassMeter meter;
  for (int f = 0; f < o_.frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    for (ItemId id = 0; id < n; ++id) tess_.run(f, id, 0);
    const double ms = ms_since(t0);
    per_frame.push_back(ms);
    total += ms;
  }
  serial_pass_usage_.push_back(meter.stop());
  serial_usage_.push_back(nz::usage_between(before, sample()));
  // The smaller of the two: a time slice lost during one probe inflates it, not the core's speed.
  serial_probe_.push_back(std::min(probe_before, nz::probe_ns_per_million_steps()));
  co_runner_.resume();
  if (o_.pin) pinning_.unpin_this_thread();
  serial_path_ms_.push_back(total);
  serial_frame_ms_.push_back(per_frame);
}

// One path of an in-process scheduler: every item recorded for the exactly-once audit.
void Measurement::run_cell_path(Cell& c) {
  if (c.child) return run_child_path(c);
  std::vector<double> per_frame, ratios;
  double total = 0;
  const nz::ProcSample before = sample();
  for (int f = 0; f < o_.frames; ++f) {
    auto item = [&](ItemId id, WorkerId w) {
      pin_as(w);
      runs_.record(id);
      tess_.run(f, id, w);
    };
    const FrameStats& st = c.instance->run_frame(item);
    std::vector<double> busy;
    for (const auto& w : st.workers) busy.push_back(static_cast<double>(w.busy_ns));
    ratios.push_back(sc::load_ratio(busy));
    const ExecutionAudit audit = runs_.audit_and_reset();
    const std::uint64_t bad = tess_.count_inconsistent();
    const double ms = account_frame(
        c, f, {st, audit, tess_.frame_triangles(), bad, bad ? tess_.first_inconsistent() : std::string()},
        wl_.serial_triangles[f]);
    per_frame.push_back(ms);
    total += ms;
  }
  c.usage += nz::usage_between(before, sample());
  unpin_caller();
  c.busy_ratio.push_back(std::move(ratios));
  c.path_ms.push_back(total);
  c.frame_ms.push_back(per_frame);
}

// openmp-static-steal: the child runs the whole path (llvm_openmp_child.hpp); the same accounting and the
// same audits, from what it reports. Its CPU time is ours, not another process's, for the noise monitor.
void Measurement::run_child_path(Cell& c) {
  std::vector<double> per_frame;
  double total = 0;
  const nz::ProcSample before = sample();
  const std::uint64_t child_ticks = c.child->cpu_ticks();
  const std::vector<sc::ChildFrame> frames = c.child->run_path();
  nz::Usage usage = nz::usage_between(before, sample());
  usage.self_ticks += c.child->cpu_ticks() - child_ticks;
  c.usage += usage;
  for (int f = 0; f < o_.frames; ++f) {
    const sc::ChildFrame& cf = frames[static_cast<std::size_t>(f)];
    const double ms = account_frame(c, f, {cf.stats, cf.audit, cf.triangles, cf.inconsistent, ""},
                                    wl_.serial_triangles[static_cast<std::size_t>(f)]);
    per_frame.push_back(ms);
    total += ms;
  }
  c.path_ms.push_back(total);
  c.frame_ms.push_back(per_frame);
}

bool Measurement::run_rounds(Progress& progress, bool auto_repeats, std::string& repeats_note) {
  measure_start_ = sample();
  const auto rounds_start = std::chrono::steady_clock::now();
  for (int r = 0; r < o_.repeats; ++r) {
    // --repeats auto was chosen from a warm-up on the machine as it was then; when others load it later, the
    // rounds slow down. Whole rounds only (every series keeps its pairs), never fewer than 5, and stop once
    // the budget is spent, so the default run stays bounded on a shared machine.
    if (auto_repeats && r >= 5 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - rounds_start).count() > o_.budget_s) {
      repeats_note += "; stopped after " + std::to_string(r) + " of " + std::to_string(o_.repeats) +
                      " rounds: the budget was spent";
      o_.repeats = r;
      break;
    }
    const std::string round = "repeat " + std::to_string(r + 1) + "/" + std::to_string(o_.repeats);
    run_serial_path();
    progress.step(round + " serial loop: " + fixed(serial_path_ms_.back(), 0) + " ms for the path");
    for (Cell& c : cells_) {
      try {
        run_cell_path(c);
      } catch (const std::exception& e) {
        std::cerr << kProgram << ": " << c.scheduler << " P=" << c.workers << ": " << e.what() << '\n';
        return false;
      }
      // Library runtimes spin a little after a parallel region; let them settle before the next scheduler.
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      progress.step(round + " P=" + std::to_string(c.workers) + " " + c.scheduler + ": " + fixed(c.path_ms.back(), 0) +
                    " ms (" + fixed(1000.0 * o_.frames / c.path_ms.back(), 1) + " frames/s)");
    }
  }
  return true;
}

void Measurement::finish() {
  // Before gnuplot, whose CPU time would count as another process's.
  measure_end_ = sample();
  co_runner_.pause();
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  at_end_ = sample();
  co_runner_.stop();
}

}  // namespace frontsteal::main_job
