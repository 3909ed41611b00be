// validate_command.cpp — the body of `frontsteal-paper validate` (validate_command.hpp).
//
// Steps: read every <study>/<set>/frontsteal.json; measure the model's constants (calibrate(): microbenchmarks;
// measure_affinity on the calibration set's path) or read them from --calibration; record one cost trace per
// path (median of --passes serial passes; kept in --traces and reused); take trace_scale from the calibration
// set; predict every cell with a model (validation.hpp) at the --threads counts; tabulate the errors.
#include "papers/validate_command.hpp"

#include "measure/machine_info.hpp"

#include <algorithm>
#include <iostream>
#include <map>

#include "papers/validation.hpp"
#include "papers/validation_report.hpp"
#include "papers/workload.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/table.hpp"

namespace frontsteal::papers {
namespace {

constexpr const char* kProgram = "frontsteal-paper validate";
constexpr const char* kDescription =
    "Predicts the main job's path times (frontsteal.json of every folder under --study) with the trace-driven "
    "simulator and reports the error of every cell. The model's constants are measured here (microbenchmarks, "
    "and the cache-affinity penalty on the calibration set's path) or read from --calibration; the only constant "
    "taken from measured path times is the trace scale, from the calibration set alone: every other set is held out.";
constexpr const char* kFooter =
    "Writes validation.md, validation.json, validation.csv and validation-calibration.txt (the constants used; pass "
    "it as --calibration to redo the predictions without measuring) into --out.\nExit status: 0 written, 1 a file "
    "could not be read or written, 2 usage.";

struct Options {
  std::string study, calibrate_on = "orbit-then-zoom-none", traces, calibration, out = "results/papers";
  int passes = 5, affinity_repeats = 6;
  std::vector<unsigned> threads{1, 2};
  std::uint64_t seed = 1;
  bool quiet = false;
};

}  // namespace

int run_validate_command(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--study", o.study, "folder of main-job result folders, each with a frontsteal.json")
      ->required()
      ->type_name("DIR");
  cli.option("--calibrate-on", o.calibrate_on, "the set (folder name) the trace scale comes from")->type_name("SET");
  cli.option("--traces", o.traces, "folder of the cost traces (recorded when missing; default OUT/traces)")
      ->type_name("DIR");
  cli.option("--calibration", o.calibration, "constants to use instead of measuring them (validation-calibration.txt)")
      ->type_name("FILE");
  cli.option("--passes", o.passes, "serial passes per trace (per surface the median)")->check(CLI::Range(1, 100));
  cli.option("--affinity-repeats", o.affinity_repeats, "paired kept/shuffled runs of the affinity measurement")
      ->check(CLI::Range(1, 100));
  cli.threads(o.threads);
  cli.seed(o.seed);
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  auto say = [&](const std::string& s) {
    if (!o.quiet) std::cerr << "validate: " << s << '\n';
  };
  try {
    // ---- the measured sets ------------------------------------------------------------------------------
    // Filled step by step; the rows point into run.sets, which is complete before the first row is made.
    ValidationRun run;
    run.machine = machine_description();
    run.sets = read_study(o.study);
    const std::vector<MeasuredSet>& sets = run.sets;
    const auto cal =
        std::find_if(sets.begin(), sets.end(), [&](const MeasuredSet& s) { return s.name == o.calibrate_on; });
    if (cal == sets.end()) cli.usage_error("--calibrate-on: no set '" + o.calibrate_on + "' under " + o.study);
    say(std::to_string(sets.size()) + " measured sets; calibration set " + cal->name);

    // ---- the constants ------------------------------------------------------------------------------------
    Overheads& ov = run.constants;
    std::optional<AffinityMeasurement>& affinity = run.affinity;
    if (!o.calibration.empty()) {
      ov = read_overheads(o.calibration);
    } else {
      ov = calibrate(machine_description(), FRONTSTEAL_GIT_COMMIT, say);
    }
    // ---- traces (and the affinity penalty, on the calibration set's path) ----------------------------------
    const std::filesystem::path trace_dir =
        o.traces.empty() ? std::filesystem::path(o.out) / "traces" : std::filesystem::path(o.traces);
    std::filesystem::create_directories(trace_dir);
    std::map<std::string, CostTrace> traces;  // by path
    for (const MeasuredSet& s : sets) {
      if (traces.count(s.path)) continue;
      const auto file = trace_dir / ("trace-" + s.path + ".txt");
      const bool need_affinity = o.calibration.empty() && s.path == cal->path;
      std::optional<PathWorkload> wl;
      if (!std::filesystem::exists(file) || need_affinity) {
        say("preparing " + s.scene + " along " + s.path);
        wl.emplace(WorkloadOptions{.scene = s.scene, .path = s.path, .data_dir = FRONTSTEAL_DATA_DIR});
      }
      if (std::filesystem::exists(file)) {
        traces[s.path] = read_cost_trace(file);
      } else {
        say("recording the trace of " + s.path + " (" + std::to_string(o.passes) + " serial passes, median)");
        traces[s.path] = record_cost_trace(*wl, o.passes, machine_description(), FRONTSTEAL_GIT_COMMIT, true);
        write_cost_trace(traces[s.path], file);
      }
      if (need_affinity) {
        say("measuring the cache-affinity penalty on " + s.path + " (lists kept vs shuffled, P = 2)");
        affinity = measure_affinity(*wl, o.affinity_repeats, o.seed, say);
        ov.affinity_penalty = std::max(0.0, affinity->penalty);
        ov.affinity_measured = true;
      }
    }
    const double trace_scale = run.trace_scale = cal->serial_ms / (traces.at(cal->path).path_cost_ns() / 1e6);
    say("trace scale (serial loop of " + cal->name + " / the trace's Σ costs): " + report::fixed_text(trace_scale, 4));

    // ---- predictions ------------------------------------------------------------------------------------------
    std::vector<ValidationRow>& rows = run.rows;
    const Overheads baseline = without_new_terms(ov);
    for (const MeasuredSet& s : sets) {
      const CostTrace& t = traces.at(s.path);
      for (const MeasuredCell& c : s.cells) {
        if (!model_of(c.scheduler)) continue;
        if (std::find(o.threads.begin(), o.threads.end(), c.workers) == o.threads.end()) continue;
        ValidationRow r{&s, c, s.name != cal->name, 0, 0};
        r.predicted_ms = predict_path_ms(t, trace_scale, ov, c.scheduler, c.workers, slowdown_of(s, c.workers), o.seed);
        r.baseline_ms = predict_path_ms(t, trace_scale, baseline, c.scheduler, c.workers, {}, o.seed);
        // The serial loop is the trace's own sum (it runs with the co-runner paused): the ratio needs no scale.
        r.predicted_vs_serial = r.predicted_ms / (t.path_cost_ns() / 1e6 * trace_scale);
        rows.push_back(r);
      }
    }
    // Ratios to queue-mutex at the same P, from the two predictions of the same set.
    for (ValidationRow& r : rows) {
      for (const ValidationRow& q : rows) {
        if (q.set == r.set && q.cell.workers == r.cell.workers && q.cell.scheduler == "queue-mutex" && &q != &r) {
          r.predicted_vs_queue = r.predicted_ms / q.predicted_ms;
        }
      }
    }
    if (rows.empty()) cli.usage_error("--threads: no measured cell at these worker counts");

    // ---- the report ---------------------------------------------------------------------------------------------
    run.calibration_set = &*cal;
    run.constants_file = o.calibration;
    run.affinity_repeats = o.affinity_repeats;
    run.trace_passes = o.passes;
    run.threads = o.threads;
    write_validation_report(run, o.out, o.quiet);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace frontsteal::papers
