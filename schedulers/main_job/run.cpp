// run.cpp — the main job's measurement (run.hpp): set-up of every cell, the serial loop's and
// the schedulers' segments (in process and in the child), the rounds, --repeats auto and the noise monitor.
#include "schedulers/main_job/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <thread>
#include <utility>

#include "measure/cpu_speed_probe.hpp"
#include "measure/heap_offset.hpp"
#include "measure/round_order.hpp"
#include "reporting/table.hpp"
#include "schedulers/main_job/round_robin_spread.hpp"

namespace frontsteal::main_job {

namespace {

namespace report = frontsteal::report;

// The worker id this thread is pinned as under --pin (-1: not pinned). Pinning happens on a thread's first
// item of a frame rather than inside each scheduler, so it reaches the threads of oneTBB and OpenMP too,
// which we do not create.
thread_local int t_pinned_as = -1;

double elapsed_s(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
  if (o.reuse) cw.extra_args.push_back("--reuse");
  return cw;
}

}  // namespace

int segments(const Options& o) { return (o.frames + o.round_frames - 1) / o.round_frames; }

int distinct_p(const Options& o) {
  std::vector<WorkerId> ps(o.threads.begin(), o.threads.end());
  std::sort(ps.begin(), ps.end());
  return static_cast<int>(std::unique(ps.begin(), ps.end()) - ps.begin());
}

std::size_t progress_steps(const Options& o) {
  return 1 + static_cast<std::size_t>(std::max(o.repeats, 1)) * static_cast<std::size_t>(segments(o));
}

Measurement::Measurement(Options& o, Workload& wl, FrameTessellator& tess, const WarmUp& warm, LimitCopies* limit)
    : o_(o),
      wl_(wl),
      tess_(tess),
      limit_copies_(limit),
      runs_(static_cast<ItemId>(wl.model.surfaces.size()), *std::max_element(o.threads.begin(), o.threads.end())),
      sampler_(static_cast<std::uint32_t>(wl.model.surfaces.size()),
               *std::max_element(o.threads.begin(), o.threads.end()), o.seed) {
  for (WorkerId p : o.threads) {
    for (const auto& name : o.schedulers) {
      Cell c;
      c.scheduler = c.label = name;
      c.workers = p;
      cells_.push_back(std::move(c));
    }
  }
  if (o.calibrate) add_calibration_arms(warm);
  if (limit_copies_) add_limit_arms();
}

// The limit arm at every P of the run (one per distinct P, like a scheduler's cell).
void Measurement::add_limit_arms() {
  std::vector<WorkerId> ps;
  for (const Cell& c : cells_) {
    if (std::find(ps.begin(), ps.end(), c.workers) == ps.end()) ps.push_back(c.workers);
  }
  std::sort(ps.begin(), ps.end());
  for (WorkerId p : ps) {
    Cell c;
    c.scheduler = kLimitName;
    c.label = "limit (" + std::to_string(p) + " serial loops at once)";
    c.role = ArmRole::kLimit;
    c.workers = p;
    cells_.push_back(std::move(c));
  }
}

// The calibration arms, at P = 1 and P = cores: the base scheduler under a second name (the A/A twin) and with
// planted work of 2, 5 and 10 % of its expected frame time, spun on the calling thread after each frame, inside
// the timed region. The steps per frame come from the warm-up's serial frame times, over min(P, cores), and the
// probe's speed now; what they realize is measured round by round (round_planted_ms), not assumed.
void Measurement::add_calibration_arms(const WarmUp& warm) {
  const double ns_per_step = nz::probe_ns_per_million_steps() / 1e6;
  std::vector<WorkerId> ps{1};
  const auto cores = static_cast<WorkerId>(hardware_cores());
  if (cores > 1) ps.push_back(cores);
  for (WorkerId p : ps) {
    auto arm = [&](ArmRole role, double planted, const std::string& label) {
      Cell c;
      c.scheduler = o_.calibrate_base;
      c.label = label;
      c.role = role;
      c.planted = planted;
      c.workers = p;
      for (int f = 0; f < o_.frames; ++f) {
        double frame_ns = 0;
        for (double ns : warm.item_ns[static_cast<std::size_t>(f)]) frame_ns += ns;
        frame_ns /= std::min<double>(p, cores);
        c.planted_steps.push_back(static_cast<std::uint64_t>(planted * frame_ns / std::max(ns_per_step, 1e-3)));
      }
      cells_.push_back(std::move(c));
    };
    arm(ArmRole::kTwin, 0, o_.calibrate_base + " (A/A twin)");
    for (int pct : {2, 5, 10}) {
      arm(ArmRole::kPlanted, pct / 100.0, o_.calibrate_base + " +" + std::to_string(pct) + " % planted");
    }
  }
}

int Measurement::co_runner_cpu() const { return o_.interference && o_.interference->pinned ? pinning_.cpu_of(0) : -1; }

void Measurement::pin_as(WorkerId w) const {
  if (o_.pin && t_pinned_as != static_cast<int>(w)) {
    pinning_.pin_this_thread(w);
    t_pinned_as = static_cast<int>(w);
  }
}

// The caller of oneTBB and OpenMP is their worker 0: under --pin it is pinned by its first item, and given
// back every CPU after each segment so the next scheduler's threads are not born confined to one core.
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
      // The chunk: --grain, else the rule of every scheduler that claims from a shared cursor (N / (100 P),
      // paper §4.1), else 1 for the chunk-1 variant.
      sc::ChildWorkload cw = child_workload(o_);
      const auto n = static_cast<ItemId>(wl_.model.surfaces.size());
      cw.grain = c.scheduler == sc::kLlvmOpenMpChunk1Name ? 1 : o_.grain ? o_.grain : sc::default_grain(n, c.workers);
      c.child = std::make_unique<sc::LlvmOpenMpChild>(c.workers, n, cw);
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

// A scheduler instance for the cell, built after a heap offset drawn afresh (measure/heap_offset.hpp): an
// instance's placement becomes noise the clusters measure instead of a constant of the run.
std::unique_ptr<sc::Scheduler> Measurement::make_instance(Cell& c, std::uint64_t draw) {
  c.instance.reset();
  c.heap_offset.redraw(o_.seed, draw);
  const sc::SchedulerInfo* info = sc::find_scheduler(c.scheduler);
  c.sample_items = info->account;
  sc::SchedulerConfig config{.workers = c.workers,
                             .items = static_cast<ItemId>(wl_.model.surfaces.size()),
                             .grain = o_.grain,
                             .seed = o_.seed};
  return info->make(config, hints_);
}

bool Measurement::start_cells(const sc::WorkloadHints& hints) {
  hints_ = hints;
  std::uint64_t draw = 0;
  for (Cell& c : cells_) {
    ++draw;
    if (c.scheduler == sc::kLlvmOpenMpName || c.scheduler == sc::kLlvmOpenMpChunk1Name) {
      start_child(c);
      continue;
    }
    if (c.role == ArmRole::kLimit) {
      const auto t0 = std::chrono::steady_clock::now();
      c.limit = std::make_unique<LimitArm>(
          *limit_copies_, c.workers, [this](WorkerId w) { pin_as(w); }, sampler_);
      c.setup_ms = ms_since(t0);
      c.limit->prime(0);
      (void)c.limit->run_frame(0);  // untimed, as every arm's first frame (the copies grew in the warm-up pass)
      (void)sampler_.take_frame();
      continue;
    }
    const auto t0 = std::chrono::steady_clock::now();
    try {
      c.instance = make_instance(c, draw);
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": cannot start " << c.label << " with P=" << c.workers << ": " << e.what() << '\n';
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
  std::erase_if(cells_, [](const Cell& c) { return !c.unavailable.empty() || (!c.instance && !c.child && !c.limit); });
  return true;
}

// The instance a cell's round names: -1 under --instance-frames 0 (one instance for the run, its rounds
// analysed as independent: the design whose intervals miss the instance effect, kept as a control).
int Measurement::instance_of(const Cell& c) const { return o_.instance_frames > 0 ? c.instance_id : -1; }

// Fresh instances of every in-process cell, each warmed up (untimed) on the frame before `first_frame`, so
// that what a scheduler carries from frame to frame (stealing's allocation, oneTBB's affinity) is what it
// would carry there; at the start of a pass the child of openmp-static-steal is restarted too (it takes half
// a second, so once a pass). The instance ids go with every round the instances run (the clusters of
// measure/paired_analysis.hpp).
void Measurement::renew_instances(int pass, int first_frame) {
  const int warm_frame = std::max(first_frame - 1, 0);
  for (Cell& c : cells_) {
    if (c.limit) continue;  // like the serial loop: one instance for the run (it carries no schedule)
    if (c.child) {
      if (first_frame != 0) continue;
      const std::uint64_t ticks = c.child->cpu_ticks();
      c.child.reset();  // stops and reaps it
      retired_child_ticks_ += ticks;
      const double first_setup_ms = c.setup_ms;
      if (!start_child(c)) throw std::runtime_error(c.label + " P=" + std::to_string(c.workers) + ": " + c.unavailable);
      c.setup_ms = first_setup_ms;
      c.instance_id = pass;
      continue;
    }
    c.instance = make_instance(c, instances_built_++);
    ++c.instance_id;
    auto warm = [&](ItemId id, WorkerId w) {
      pin_as(w);
      tess_.run(warm_frame, id, w);
    };
    c.instance->run_frame(warm);
    unpin_caller();
  }
}

bool Measurement::start_interference() {
  if (!o_.interference) return true;
  try {
    co_runner_ = fi::CoRunner::start(
        {.duty = o_.interference->duty, .period_us = 10'000, .cpu = o_.interference->pinned ? pinning_.cpu_of(0) : -1});
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

namespace {

// The frames [first, last) of segment s.
std::pair<int, int> segment_frames(const Options& o, int s) {
  return {s * o.round_frames, std::min(o.frames, (s + 1) * o.round_frames)};
}

}  // namespace

void Measurement::begin_pass() {
  serial_frame_ms_.emplace_back(static_cast<std::size_t>(o_.frames), 0.0);
  serial_path_ms_.push_back(0);
  serial_usage_.emplace_back();
  serial_pass_usage_.emplace_back();
  pass_probe_min_ = 0;
  for (Cell& c : cells_) {
    c.frame_ms.emplace_back(static_cast<std::size_t>(o_.frames), 0.0);
    c.path_ms.push_back(0);
    if (!c.child && !c.limit) c.busy_ratio.emplace_back(static_cast<std::size_t>(o_.frames), 0.0);
  }
}

// The serial reference (T1) on one segment: a plain loop on this thread, the co-runner paused.
void Measurement::run_serial_segment(std::size_t round, int segment, double probe) {
  const auto n = static_cast<ItemId>(wl_.model.surfaces.size());
  const auto [first, last] = segment_frames(o_, segment);
  pin_as(0);
  tess_.prime(first);  // --reuse: the same kept state for every arm of the round (untimed)
  co_runner_.pause();  // T1 is the undisturbed reference (no-op without --interference)
  const nz::ProcSample before = sample();
  const nz::PassMeter meter;
  double total = 0, sampled_ms = 0;
  for (int f = first; f < last; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    for (ItemId id = 0; id < n; ++id) {
      sampler_.run(
          id, 0, [] {}, [&] { tess_.run(f, id, 0); });
    }
    const double ms = ms_since(t0);
    sampled_ms += sampler_.take_frame().work_ns / 1e6;
    // The serial loop runs once per P in each segment: the pass's figures are the mean of those runs.
    serial_frame_ms_.back()[static_cast<std::size_t>(f)] += ms / static_cast<double>(ps_.size());
    total += ms;
  }
  serial_pass_usage_.back() += meter.stop();
  serial_usage_.back() += nz::usage_between(before, sample());
  co_runner_.resume();
  unpin_caller();
  serial_path_ms_.back() += total / static_cast<double>(ps_.size());
  serial_rounds_.add(round, total, probe, segment);
  serial_sampled_.add(round, sampled_ms, probe, segment);
  pass_probe_min_ = pass_probe_min_ > 0 ? std::min(pass_probe_min_, probe) : probe;
}

// One segment of an in-process scheduler: every item recorded for the exactly-once audit; every frame timed by
// this thread's clock around run_frame and the planted work, the audits after the clock stops.
void Measurement::run_cell_segment(Cell& c, std::size_t round, int segment, double probe) {
  if (c.child) return run_child_segment(c, round, segment, probe);
  if (c.limit) return run_limit_segment(c, round, segment, probe);
  const auto [first, last] = segment_frames(o_, segment);
  tess_.prime(first);  // --reuse: the same kept state for every arm of the round (untimed)
  double total = 0, planted_total = 0, sampled_ms = 0;
  const nz::ProcSample before = sample();
  for (int f = first; f < last; ++f) {
    // The harness's checks (pinning, the exactly-once count) and the work, timed on the sampled surfaces (not at
    // all for the variant that measures what the account costs).
    auto sampled = [&](ItemId id, WorkerId w) {
      sampler_.run(
          id, w,
          [&] {
            pin_as(w);
            runs_.record(id, w);
          },
          [&] { tess_.run(f, id, w); });
    };
    auto plain = [&](ItemId id, WorkerId w) {
      pin_as(w);
      runs_.record(id, w);
      tess_.run(f, id, w);
    };
    const std::uint64_t steps = c.planted_steps.empty() ? 0 : c.planted_steps[static_cast<std::size_t>(f)];
    const TimedFrame timed =
        c.sample_items ? time_frame(*c.instance, sampled, steps) : time_frame(*c.instance, plain, steps);
    const FrameStats& st = *timed.stats;
    const double planted_ms = timed.planted_ns / 1e6;
    const double ms = timed.frame_ns / 1e6 + planted_ms;
    const double own_ms = static_cast<double>(st.wall_ns) / 1e6;
    const double gap = std::fabs(timed.frame_ns / 1e6 - own_ms);
    c.clock_gap_max_ms = std::max(c.clock_gap_max_ms, gap);
    if (gap > kClockGapBoundMs + 0.05 * own_ms) ++c.clock_gap_frames;
    measure::ItemSamples samples = sampler_.take_frame();
    sampled_ms += samples.work_ns / 1e6;
    c.account.add_frame(st, timed.frame_ns, std::move(samples));
    std::vector<double> busy;
    for (const auto& w : st.workers) busy.push_back(static_cast<double>(w.busy_ns));
    c.busy_ratio.back()[static_cast<std::size_t>(f)] = sc::load_ratio(busy);
    const ExecutionAudit audit = runs_.audit_and_reset();
    const std::uint64_t bad = tess_.count_inconsistent();
    account_frame(c, f, {st, audit, tess_.frame_triangles(), bad, bad ? tess_.first_inconsistent() : std::string()},
                  wl_.serial_triangles[static_cast<std::size_t>(f)]);
    c.frame_ms.back()[static_cast<std::size_t>(f)] = ms;
    total += ms;
    planted_total += planted_ms;
  }
  c.usage += nz::usage_between(before, sample());
  unpin_caller();
  c.path_ms.back() += total;
  c.rounds.add(round, total, probe, segment, instance_of(c));
  c.sampled.add(round, sampled_ms, probe, segment, instance_of(c));
  c.round_planted_ms.push_back(planted_total);
}

// The limit arm on one segment: P serial loops at once. Its rounds hold P x L per frame (L the throughput limit,
// limit_arm.hpp), so that rounds / P is comparable with a scheduler's time; `limit_wall` holds the arm's wall time
// from the release to the last copy's end. Every copy is audited against the serial loop like a scheduler's frame.
void Measurement::run_limit_segment(Cell& c, std::size_t round, int segment, double probe) {
  const auto [first, last] = segment_frames(o_, segment);
  c.limit->prime(first);  // --reuse: every copy from the same kept state (untimed)
  double total = 0, wall_total = 0, sampled_ms = 0;
  const nz::ProcSample before = sample();
  for (int f = first; f < last; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    const LimitFrame& lf = c.limit->run_frame(f);
    const double wall_ms = ms_since(t0);
    const double ms = static_cast<double>(c.workers) * lf.throughput_ns() / 1e6;
    sampled_ms += sampler_.take_frame().work_ns / 1e6 / static_cast<double>(c.workers);
    const auto copies = static_cast<double>(lf.copy_ns.size());
    double mean_ns = 0, slowest_ns = 0;
    for (std::size_t w = 0; w < lf.copy_ns.size(); ++w) {
      mean_ns += static_cast<double>(lf.copy_ns[w]) / copies;
      slowest_ns = std::max(slowest_ns, static_cast<double>(lf.copy_ns[w]));
      const std::string at = "frame " + std::to_string(f) + ", copy " + std::to_string(w) + ": ";
      if (lf.inconsistent[w] > 0) {
        c.tessellation_inconsistencies += lf.inconsistent[w];
        if (c.first_problem.empty())
          c.first_problem = at + std::to_string(lf.inconsistent[w]) + " surfaces fail the tessellation audit";
      }
      if (lf.triangles[w] != wl_.serial_triangles[static_cast<std::size_t>(f)]) {
        ++c.triangle_mismatches;
        if (c.first_problem.empty()) {
          c.first_problem = at + std::to_string(lf.triangles[w]) + " triangles, serial loop made " +
                            std::to_string(wl_.serial_triangles[static_cast<std::size_t>(f)]);
        }
      }
    }
    wall_total += wall_ms;
    c.limit_copy_spread_sum += mean_ns > 0 ? slowest_ns / mean_ns : 1.0;
    c.limit_copy_time_sum.resize(lf.copy_ns.size(), 0.0);
    for (std::size_t w = 0; w < lf.copy_ns.size(); ++w) {
      c.limit_copy_time_sum[w] += mean_ns > 0 ? static_cast<double>(lf.copy_ns[w]) / mean_ns : 1.0;
    }
    ++c.frames_run;
    c.frame_ms.back()[static_cast<std::size_t>(f)] = ms;
    total += ms;
  }
  c.usage += nz::usage_between(before, sample());
  unpin_caller();
  c.path_ms.back() += total;
  c.rounds.add(round, total, probe, segment);
  c.limit_wall.add(round, wall_total, probe, segment);
  c.sampled.add(round, sampled_ms, probe, segment);
  c.round_planted_ms.push_back(0);
}

// openmp-static-steal: the child runs the segment (llvm_openmp_child.hpp); the same accounting and the same
// audits, from what it reports. Its frames are timed by its own clock: this process sees only the exchange. Its
// CPU time is ours, not another process's, for the noise monitor.
void Measurement::run_child_segment(Cell& c, std::size_t round, int segment, double probe) {
  const auto [first, last] = segment_frames(o_, segment);
  double total = 0;
  const nz::ProcSample before = sample();
  const std::uint64_t child_ticks = c.child->cpu_ticks();
  const std::vector<sc::ChildFrame> frames = c.child->run_frames(first, last);
  nz::Usage usage = nz::usage_between(before, sample());
  usage.self_ticks += c.child->cpu_ticks() - child_ticks;
  c.usage += usage;
  for (int f = first; f < last; ++f) {
    const sc::ChildFrame& cf = frames[static_cast<std::size_t>(f - first)];
    const double ms = account_frame(c, f, {cf.stats, cf.audit, cf.triangles, cf.inconsistent, ""},
                                    wl_.serial_triangles[static_cast<std::size_t>(f)]);
    c.account.add_frame(cf.stats, static_cast<double>(cf.stats.wall_ns), {});  // its own clock: no other here
    c.frame_ms.back()[static_cast<std::size_t>(f)] = ms;
    total += ms;
  }
  c.path_ms.back() += total;
  c.rounds.add(round, total, probe, segment, instance_of(c));
  c.round_planted_ms.push_back(0);
}

// After the first pass: the planted work was sized from the serial frame times over min(P, cores), which
// overstates a frame's time at P > 1 (the schedulers are not perfectly efficient) and understates what the
// planted fraction should be. Each planted arm's steps are rescaled by what it realized in the first pass (its
// planted time over the rest of its time), so that later passes plant the nominal fraction; the realized size
// over the whole run is measured and reported either way.
void Measurement::resize_planted_work() {
  for (Cell& c : cells_) {
    if (c.role != ArmRole::kPlanted) continue;
    double planted = 0, rest = 0;
    for (std::size_t k = 0; k < c.rounds.size(); ++k) {
      planted += c.round_planted_ms[k];
      rest += c.rounds.time[k] - c.round_planted_ms[k];
    }
    if (!(planted > 0) || !(rest > 0)) continue;
    const double scale = c.planted / (planted / rest);
    for (std::uint64_t& steps : c.planted_steps) steps = static_cast<std::uint64_t>(static_cast<double>(steps) * scale);
  }
}

// One round: the serial loop and every arm at P once on the segment, in this round's order. Before each arm: a
// short pause (library runtimes spin a little after a parallel region; let them settle), then the CPU speed
// probe on this thread — before the arm, so that it cannot depend on which arm runs.
void Measurement::run_round(std::size_t round, WorkerId p, int segment) {
  std::vector<Cell*> arms{nullptr};  // nullptr: the serial loop
  for (Cell& c : cells_) {
    if (c.workers == p) arms.push_back(&c);
  }
  for (std::size_t arm : measure::round_order(arms.size(), o_.seed, round, o_.order)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    pin_as(0);  // pinned runs: the probe on worker 0's CPU, where the serial loop and every P's worker 0 run
    const double probe = nz::probe_ns_per_million_steps();
    if (!arms[arm]) {
      run_serial_segment(round, segment, probe);
      continue;
    }
    Cell& c = *arms[arm];
    try {
      run_cell_segment(c, round, segment, probe);
    } catch (const std::exception& e) {
      throw std::runtime_error(c.label + " P=" + std::to_string(c.workers) + ": " + e.what());
    }
  }
}

// --repeats auto after the pilot: the spread of every comparison's per-round log-ratio (each cell against the
// serial loop and against queue-mutex at its P; calibration arms against their base), the 90th percentile of
// them, and the rounds that decide at that spread with 80 % power (measure::rounds_to_decide: an equivalent pair
// called equivalent, a change of twice the margin called faster or slower). Only the spread is looked at,
// never the estimates, so sizing the run does not bias its verdicts.
int Measurement::passes_from_pilot(double pass_s, std::string& note) const {
  std::vector<double> sds;
  auto spread = [&](const measure::ArmRounds& a, const measure::ArmRounds& b) {
    const measure::PairedResult r = measure::analyze_pairs(measure::pair_rounds(a, b), analysis_settings(o_));
    if (r.chosen().valid) sds.push_back(r.chosen().sd);
  };
  for (const Cell& c : cells_) {
    spread(c.rounds, serial_rounds_);
    for (const Cell& q : cells_) {
      if (&q != &c && q.workers == c.workers && q.role == ArmRole::kScheduler &&
          q.scheduler == (c.role == ArmRole::kScheduler ? "queue-mutex" : o_.calibrate_base)) {
        spread(c.rounds, q.rounds);
      }
    }
  }
  std::sort(sds.begin(), sds.end());
  const double sd90 = sds.empty() ? 0.0 : stats::quantile_sorted(sds, 0.9);
  const double rounds = measure::rounds_to_decide(sd90, o_.margin);
  const int wanted = static_cast<int>(std::ceil(rounds / segments(o_)));
  const int fit = static_cast<int>(o_.budget_s / std::max(pass_s, 1e-9));
  const int passes = std::clamp(wanted, kMinPasses, std::max(kMinPasses, fit));
  note = "auto: a pilot of " + std::to_string(kPilotPasses) + " passes (" +
         std::to_string(kPilotPasses * segments(o_)) + " rounds per comparison, " + fixed(pass_s, 1) +
         " s per pass): per-round log-ratio spread " + fixed(100 * sd90, 2) + " % (90th percentile of " +
         std::to_string(sds.size()) + " comparisons) -> " + std::to_string(static_cast<int>(std::ceil(rounds))) +
         " rounds decide against +-" + fixed(100 * o_.margin, 1) + " % with 80 % power; budget " +
         fixed(o_.budget_s, 0) + " s fits " + std::to_string(fit) + " passes; chose " + std::to_string(passes);
  return passes;
}

bool Measurement::run_rounds(Progress& progress, bool auto_repeats, std::string& repeats_note) {
  measure_start_ = sample();
  const auto rounds_start = std::chrono::steady_clock::now();
  const int segs = segments(o_);
  for (const Cell& c : cells_) {
    if (std::find(ps_.begin(), ps_.end(), c.workers) == ps_.end()) ps_.push_back(c.workers);
  }
  std::sort(ps_.begin(), ps_.end());
  if (auto_repeats) o_.repeats = kPilotPasses;
  progress.set_total(progress_steps(o_));
  for (int r = 0; r < o_.repeats; ++r) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - rounds_start).count();
    // The budget is checked at pass boundaries: whole passes only (every arm keeps every frame), never fewer
    // than kMinPasses.
    if (auto_repeats && r >= kMinPasses && elapsed > o_.budget_s) {
      repeats_note += "; stopped after " + std::to_string(r) + " of " + std::to_string(o_.repeats) +
                      " passes: the budget was spent";
      o_.repeats = r;
      break;
    }
    begin_pass();
    for (int s = 0; s < segs; ++s) {
      // Fresh instances where a new stretch of --instance-frames frames starts (the first pass's first
      // instances are start_cells' own).
      const int stretch_first = segment_frames(o_, s).first;
      const bool new_stretch =
          o_.instance_frames > 0 &&
          (s == 0 || stretch_first / o_.instance_frames != segment_frames(o_, s - 1).first / o_.instance_frames);
      if (new_stretch && (r > 0 || s > 0)) {
        try {
          renew_instances(r, stretch_first);
        } catch (const std::exception& e) {
          std::cerr << kProgram << ": " << e.what() << '\n';
          return false;
        }
      }
      // The P of this segment's rounds, in an order of their own (the arms of different P are never compared
      // within a round, so each P's round holds only its arms and the serial loop: shorter rounds, closer pairs).
      const std::size_t segment_id =
          static_cast<std::size_t>(r) * static_cast<std::size_t>(segs) + static_cast<std::size_t>(s);
      for (std::size_t pi : measure::round_order(ps_.size(), o_.seed ^ 0x5eedull, segment_id, o_.order)) {
        const std::size_t round = rounds_done_++;
        try {
          run_round(round, ps_[pi], s);
        } catch (const std::exception& e) {
          std::cerr << kProgram << ": " << e.what() << '\n';
          return false;
        }
      }
      const auto [first, last] = segment_frames(o_, s);
      progress.step("pass " + std::to_string(r + 1) + "/" + std::to_string(o_.repeats) + ", frames " +
                    std::to_string(first) + "-" + std::to_string(last - 1) + ": rounds " +
                    std::to_string(rounds_done_ - ps_.size() + 1) + "-" + std::to_string(rounds_done_) +
                    " (one per P, " + measure::to_string(o_.order) + " order); serial loop " +
                    fixed(serial_rounds_.time.back(), 1) + " ms");
    }
    serial_probe_.push_back(pass_probe_min_);
    if (r == 0) resize_planted_work();
    if (auto_repeats && r + 1 == kPilotPasses) {
      o_.repeats = passes_from_pilot(elapsed_s(rounds_start) / kPilotPasses, repeats_note);
      progress.set_total(progress_steps(o_));
      if (!o_.quiet) std::fprintf(stderr, "frontsteal: %s\n", repeats_note.c_str());
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
