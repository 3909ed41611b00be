// json.cpp — frontsteal.json (json.hpp).
#include "schedulers/main_job/json.hpp"

#include <cmath>

#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"
#include "schedulers/main_job/rounds_json.hpp"

namespace frontsteal::main_job {

namespace {

using report::Json;

// frontsteal.json's schema (docs/results-schema.md). 4: the limit arm and the loss account; 3: rounds and margin
// verdicts (answer, design, per-round data, each comparison's raw and adjusted interval); 2: the common header of
// reporting/.
constexpr int kSchemaVersion = 4;

Json usage_json(const nz::Usage& u, const nz::Thresholds& t) {
  return {{"wall_s", u.wall_s},
          {"windows", u.windows},
          {"ticks", u.total_ticks},
          {"other_share", u.other_share()},
          {"steal_share", u.steal_share()},
          {"busy", nz::assess(u, t).busy}};
}

// {"worst", "worst_frame", "median", "per_frame"}; infinity (a worker with nothing) is null.
Json spread_json(const sc::CostSpread& c) {
  auto number = [](double v) { return std::isinf(v) ? Json(nullptr) : Json(v); };
  Json per_frame = Json::array();
  for (double v : c.per_frame) per_frame.push_back(number(v));
  return {{"worst", number(c.worst)},
          {"worst_frame", c.worst_frame},
          {"median", number(c.median)},
          {"per_frame", per_frame}};
}

// Per copy of the limit arm, its time over the mean copy's, averaged over frames: how the cores' speeds differ.
Json copy_relative_time(const Cell& c) {
  Json out = Json::array();
  for (double sum : c.limit_copy_time_sum) out.push_back(c.frames_run ? sum / static_cast<double>(c.frames_run) : 1.0);
  return out;
}

Json inflation_json(const Inflation& i) {
  const measure::LogInterval& li = i.c.chosen();
  return {{"factor", li.ratio()}, {"ci95_low", li.ratio_low()}, {"ci95_high", li.ratio_high()}, {"rounds", i.c.rounds}};
}

// The loss account of one row: every term's share of P x T and its ns, the closure, the sampled timings it used,
// the work's inflation against the serial loop and its split by the limit's.
Json account_json(const Account& acc, const AccountSums& sums) {
  Json shares = Json::object(), ns = Json::object();
  for (std::size_t i = 0; i < kTerms; ++i) {
    const auto t = static_cast<Term>(i);
    shares[name(t)] = acc.terms.share(t);
    ns[name(t)] = acc.terms.ns[i];
  }
  return {{"shares", shares},
          {"ns", ns},
          {"available_ns", acc.terms.available_ns},
          {"closes", acc.terms.closes()},
          {"closure_bound", kClosureBound},
          {"frames", sums.frames},
          {"frames_not_closing", sums.frames_open},
          {"worst_frame_unaccounted", sums.worst_frame_open},
          {"phases_timed", acc.terms.phases_timed},
          {"checks_per_item_ns", acc.terms.checks_per_item_ns},
          {"claim_per_item_ns", acc.terms.claim_per_item_ns},
          {"sampled_items", acc.terms.samples},
          {"sampled_gaps", acc.terms.gaps},
          {"inflation", acc.inflation ? inflation_json(*acc.inflation) : Json(nullptr)},
          {"work_at_limit", acc.split_by_limit ? Json(acc.work_at_limit) : Json(nullptr)},
          {"inflation_beyond_limit", acc.split_by_limit ? Json(acc.inflation_beyond_limit) : Json(nullptr)}};
}

}  // namespace

// frontsteal.json: the set-up, the round-robin spread, the noise, the serial loop, and per scheduler and P the
// data table's row with the structured values added (comparisons, noise, per worker, per pass, per round, per frame).
Json results_json(const Measured& m, const Analysis& a, const report::Table& data) {
  const Options& o = m.o;
  Json js = report::document(kProgram, kSchemaVersion, "measured", FRONTSTEAL_GIT_COMMIT);
  js["machine"] = a.machine;
  js["scene"] = o.scene;
  js["surfaces"] = m.wl.model.surfaces.size();
  js["frames"] = o.frames;
  js["repeats"] = o.repeats;
  js["tolerance_px"] = o.tolerance;
  js["image"] = {o.width, o.height};
  js["hardware_threads"] = m.cores;
  js["repeats_note"] = m.repeats_note;
  js["answer"] = a.answer;
  js["design"] = {
      {"line", a.design_line},
      {"rounds", m.serial_rounds.size()},
      {"passes", o.repeats},
      {"round_frames", o.round_frames},
      {"instance_frames", o.instance_frames},
      {"order", measure::to_string(o.order)},
      {"seed", o.seed},
      {"margin_pct", 100 * o.margin},
      {"interval", std::string("Student t on the per-round log-ratios (") + measure::to_string(o.estimator) +
                       "), segments as blocks" +
                       (o.instance_frames > 0 ? ", cluster-robust over the schedulers' instances" : "")},
      {"covariate", o.adjust ? "CPU speed probe before each arm (regression adjustment)" : "none (--no-adjust)"},
      {"clock", "harness steady_clock around run_frame (openmp-static-steal: the child's clock)"},
      {"median_mde80_pct", a.median_mde_pct}};
  js["notes"] = a.notes;
  js["pinned"] = o.pin;
  js["path"] = ts::name(o.path);
  js["path_note"] = a.path_line;
  if (o.interference) {
    js["interference"] = {{"on", true},
                          {"duty_pct", 100 * o.interference->duty},
                          {"setup", o.interference->pinned ? "pinned" : "unpinned"},
                          {"period_ms", 10},
                          {"co_runner_cpu", m.co_runner_cpu},
                          {"co_runner_core_share_measured", a.co_runner_core_share},
                          {"serial_loop", "co-runner paused"},
                          {"note", a.interference_line}};
  } else {
    js["interference"] = {{"on", false}};
  }
  Json spreads = Json::array();
  for (const SpreadRow& r : a.spreads) {
    spreads.push_back({{"workers", r.p},
                       {"serial_item_times", spread_json(r.measured)},
                       {"estimates", spread_json(r.estimated)},
                       {"round_robin_busy", r.busy ? spread_json(*r.busy) : Json(nullptr)}});
  }
  js["round_robin_spread"] = spreads;
  js["noise"] = {{"before", usage_json(a.before_usage, o.noise)},
                 {"during", usage_json(a.during_usage, o.noise)},
                 {"after", usage_json(a.after_usage, o.noise)},
                 {"co_runner_share_during", a.during_usage.known_share()},
                 {"load1_before", m.at_start.load1},
                 {"load1_after", m.at_end.load1},
                 {"serial_spread_pct", 100 * a.serial_spread},
                 {"cpu_probe_ns_per_million_steps", m.serial_probe},
                 {"cpu_probe_spread_pct", 100 * a.spread_diagnosis.probe_spread},
                 {"cpu_probe_correlation", a.spread_diagnosis.correlation},
                 {"cpu_varied", a.spread_diagnosis.cpu_varied},
                 {"cpu_probe_follows_passes", a.spread_diagnosis.probe_follows_passes},
                 {"serial_passes", nz::pass_usage_columns(m.serial_pass_usage)},
                 {"serial_same_work_on_cpu", a.spread_diagnosis.same_work_on_cpu},
                 {"spread_diagnosis", a.spread_diagnosis.line},
                 {"busy_threshold_pct", 100 * o.noise.other_share},
                 {"spread_threshold_pct", 100 * o.noise.spread},
                 {"verdicts", a.verdicts},
                 {"unreliable_verdicts", a.unreliable},
                 {"warnings", a.noise_warnings}};
  js["serial"] = {{"path_ms", a.t1_ms},
                  {"path_ms_per_repeat", m.serial_path_ms},
                  {"rounds", rounds_json(m.serial_rounds)},
                  {"triangles_per_frame", m.wl.serial_triangles},
                  {"inconsistent_surfaces_per_frame", m.wl.serial_inconsistencies},
                  {"capped_surfaces_per_frame", m.wl.serial_capped},
                  {"reuse", o.reuse},
                  {"remade_surfaces_per_frame", m.wl.serial_remade},
                  {"max_steps", m.wl.settings.max_steps},
                  {"frame_ms_median", frame_medians(m.serial_frame_ms, o.frames)}};
  const Json rows = data.json();  // [0] is the serial loop, already under "serial"
  Json results = Json::array();
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const Row& r = a.rows[i];
    const Cell& c = *r.cell;
    Json row = rows.at(i + 1);
    row["items_stolen"] = c.totals.items_stolen;
    row["vs_serial"] = r.vs_serial.json();
    row["vs_queue_mutex"] = r.vs_queue ? r.vs_queue->json() : Json(nullptr);
    row["noise"] = usage_json(c.usage, o.noise);
    Json per_worker = Json::array();
    for (const WorkerFrameStats& ws : c.per_worker) {
      per_worker.push_back({{"items", ws.items_processed},
                            {"claims", ws.claims},
                            {"busy_ms", ws.busy_ns / 1e6},
                            {"cpu_ms", ws.cpu_ns / 1e6},
                            {"active_ms", ws.active_ns / 1e6},
                            {"wake_ms", ws.wake_ns / 1e6},
                            {"search_ms", ws.search_ns / 1e6},
                            {"steal_ms", ws.steal_ns / 1e6},
                            {"transient_wait_ms", ws.transient_wait_ns / 1e6},
                            {"termination_ms", ws.termination_ns / 1e6}});
    }
    row["per_worker"] = per_worker;
    row["path_ms_per_repeat"] = c.path_ms;
    row["rounds"] = rounds_json(c.rounds);
    // openmp-static-steal is timed by its own process: there is no second clock to check it against.
    row["clock_check"] = c.child ? Json(nullptr)
                                 : Json{{"max_gap_ms", c.clock_gap_max_ms},
                                        {"frames_beyond_bound", c.clock_gap_frames},
                                        {"bound", "1 ms + 5 % of the scheduler's own frame time"}};
    row["frame_ms_median"] = frame_medians(c.frame_ms, o.frames);
    row["sampled_rounds"] = rounds_json(c.sampled);
    row["vs_limit"] = r.vs_limit ? r.vs_limit->json() : Json(nullptr);
    row["vs_limit_wall"] = r.vs_limit_wall ? r.vs_limit_wall->json() : Json(nullptr);
    row["limit_efficiency"] = r.vs_limit && r.vs_limit->c.chosen().valid
                                  ? Json{{"value", r.limit_efficiency()},
                                         {"ci95_low", r.limit_efficiency_low()},
                                         {"ci95_high", r.limit_efficiency_high()}}
                                  : Json(nullptr);
    row["account"] = account_json(r.account, c.account);
    results.push_back(std::move(row));
  }
  js["results"] = results;
  Json limits = Json::array();
  for (const LimitRow& l : a.limits) {
    limits.push_back({{"workers", l.cell->workers},
                      {"path_ms", l.path_ms},
                      {"speedup", l.speedup},
                      {"wall_speedup", l.wall_speedup},
                      {"wall_rounds", rounds_json(l.cell->limit_wall)},
                      {"vs_serial", l.vs_serial.json()},
                      {"inflation", l.inflation ? inflation_json(*l.inflation) : Json(nullptr)},
                      {"copy_spread", l.copy_spread},
                      {"copy_relative_time", copy_relative_time(*l.cell)},
                      {"audit_failures", l.cell->triangle_mismatches + l.cell->tessellation_inconsistencies},
                      {"path_ms_per_repeat", l.cell->path_ms},
                      {"rounds", rounds_json(l.cell->rounds)},
                      {"sampled_rounds", rounds_json(l.cell->sampled)},
                      {"frame_ms_median", frame_medians(l.cell->frame_ms, o.frames)}});
  }
  js["limits"] = limits;
  js["scale_answer"] = a.scale_answer;
  Json not_available = Json::array();
  for (const Cell& c : m.not_available) {
    not_available.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"reason", c.unavailable}});
  }
  js["not_available"] = not_available;
  Json children = Json::array();
  for (const Cell& c : m.cells) {
    if (c.child)
      children.push_back({{"scheduler", c.scheduler}, {"workers", c.workers}, {"ready", c.child->ready_line()}});
  }
  js["child_processes"] = children;
  if (!a.calibration.empty()) js["calibration"] = calibration_json(m, a)["arms"];
  return js;
}

Json calibration_json(const Measured& m, const Analysis& a) {
  Json js = report::document(kProgram, kSchemaVersion, "measured", FRONTSTEAL_GIT_COMMIT);
  js["machine"] = a.machine;
  js["design"] = a.design_line;
  js["base"] = m.o.calibrate_base;
  js["hardware_threads"] = m.cores;
  js["margin_pct"] = 100 * m.o.margin;
  js["rounds"] = m.serial_rounds.size();
  js["seed"] = m.o.seed;
  Json arms = Json::array();
  for (const CalibrationRow& r : a.calibration) {
    arms.push_back({{"workers", r.workers},
                    {"arm", r.label},
                    {"planted_pct", 100 * r.nominal},
                    {"realized_pct", 100 * r.realized},
                    {"found", r.found()},
                    {"covered", r.covered()},
                    {"right_verdict", r.right()},
                    {"comparison", r.result.json()},
                    {"rounds", {{"candidate", rounds_json(*r.candidate)}, {"reference", rounds_json(*r.reference)}}}});
  }
  js["arms"] = arms;
  return js;
}

}  // namespace frontsteal::main_job
