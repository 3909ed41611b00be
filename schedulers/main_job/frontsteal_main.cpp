// frontsteal — the main job: every scheduler on the real tessellation workload, side by side.
//
// A scene (default: the generated 15,906-surface plant, the size of the paper's largest Fig. 8 model) is
// tessellated along a deterministic camera path — half an orbit of the whole model, half a zoom into a small
// corner region, where round robin becomes badly imbalanced (paper §3) — by a serial loop (T1) and by every
// scheduler at P = 1 … cores and oversubscribed, in rounds: every arm once per segment of the path, in a fresh
// random order each round (run.hpp); the verdicts come from the per-round paired log-ratios against a
// margin (measure/paired_analysis.hpp). Every frame is
// audited: each surface ran exactly once, the frame's triangle count equals the serial loop's, and every
// surface passed the tessellation's own audit (trimmed pieces tiled exactly, area equal to the trim loops').
//
// The pieces, one concept each: the options (options.hpp, CLI11), the workload and its serial
// warm-up pass (workload.hpp), the measurement (run.hpp) and the report
// (report.hpp: table, markdown, CSV, JSON and gnuplot through reporting/). This file only joins them,
// after handing any other subcommand to its program (subcommands.hpp).
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "measure/noise_monitor.hpp"
#include "schedulers/main_job/options.hpp"
#include "schedulers/main_job/progress.hpp"
#include "schedulers/main_job/report.hpp"
#include "schedulers/main_job/run.hpp"
#include "schedulers/main_job/workload.hpp"
#include "schedulers/main_job/subcommands.hpp"

namespace mj = frontsteal::main_job;
namespace nz = frontsteal::noise;

int main(int argc, char** argv) {
  // `frontsteal X ...` runs program X in this process's place (subcommands.hpp); `run` and none are the main job.
  mj::Dispatch d = mj::dispatch(argc, argv);
  if (d.exit_status) return *d.exit_status;
  std::vector<char*> args;
  for (std::string& a : d.args) args.push_back(a.data());
  args.push_back(nullptr);
  mj::Options o = mj::parse_options(static_cast<int>(d.args.size()), args.data());
  const unsigned cores = frontsteal::hardware_cores();
  // The noise monitor's "before" window runs from here to the first measured repeat (loading, warm-up,
  // scheduler set-up: our own work, so anything else that ran meanwhile was someone else's).
  const nz::ProcSample at_start = nz::sample_now();

  // The workload, and the serial warm-up pass: the reference triangle counts, and T1 for --repeats auto.
  mj::PreparedScene scene = mj::prepare_scene(o, cores);
  mj::FrameTessellator tess(scene.wl, *std::max_element(o.threads.begin(), o.threads.end()));
  mj::Progress progress(o.quiet, mj::progress_steps(o));
  // The limit arm's copies are made here, before the schedulers, and grown in the warm-up pass beside the
  // scene's buffers (limit_arm.hpp: where their memory lies).
  std::optional<mj::LimitCopies> limit_copies;
  if (o.limit) limit_copies.emplace(scene.wl, *std::max_element(o.threads.begin(), o.threads.end()), o.reuse);
  mj::LimitCopies* copies = limit_copies ? &*limit_copies : nullptr;
  const mj::WarmUp warm = mj::warm_up(o, scene.wl, tess, copies);
  const bool auto_repeats = o.repeats == 0;
  std::string repeats_note = auto_repeats ? "auto" : "set by --repeats";
  progress.set_total(mj::progress_steps(o));
  progress.step("serial warm-up pass (reference triangle counts, " +
                std::to_string(static_cast<int>(warm.seconds * 1000)) + " ms); " +
                (auto_repeats ? std::string("a pilot of ") + std::to_string(mj::kPilotPasses) + " passes sizes the run"
                              : std::to_string(o.repeats) + " passes") +
                "; a pass is " + std::to_string(mj::segments(o)) + " segments x " + std::to_string(mj::distinct_p(o)) +
                " P = " + std::to_string(mj::segments(o) * mj::distinct_p(o)) + " rounds");

  // The schedulers, the co-runner, the rounds; the children and the co-runner are reaped by `run` on every way
  // out of main.
  mj::Measurement run(o, scene.wl, tess, warm, copies);
  if (!run.start_cells(scene.hints) || !run.start_interference()) return 1;
  if (!run.run_rounds(progress, auto_repeats, repeats_note)) return 1;
  run.finish();

  const mj::Measured measured{o,
                              cores,
                              scene.wl,
                              scene.wl.dense,
                              warm.item_ns,
                              warm.item_estimate,
                              run.serial_path_ms(),
                              run.serial_frame_ms(),
                              run.serial_usage(),
                              run.serial_probe(),
                              run.serial_pass_usage(),
                              run.serial_rounds(),
                              run.serial_sampled(),
                              run.cells(),
                              run.not_available(),
                              at_start,
                              run.measure_start(),
                              run.measure_end(),
                              run.at_end(),
                              repeats_note,
                              run.co_runner_cpu()};
  return mj::write_results(measured, progress.seconds());
}
