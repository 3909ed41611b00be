// paired_rounds.cpp — the rounds of paired_rounds.hpp and their comparisons.
#include "distributed/paired_rounds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>

#include "distributed/rank_watchdog.hpp"
#include "distributed/scheduler_run.hpp"
#include "measure/cpu_speed_probe.hpp"
#include "measure/machine_info.hpp"
#include "measure/round_order.hpp"

namespace frontsteal::mpi {
namespace {

std::string planted_label(const Options& o) {
  char pct[32];
  std::snprintf(pct, sizeof pct, "%g", o.planted_pct);
  return o.reference + " +" + pct + " % planted";
}

}  // namespace

std::vector<PairedArm> paired_arms(const Options& o) {
  std::vector<PairedArm> arms;
  for (const std::string& s : o.schedulers) {
    if (std::none_of(arms.begin(), arms.end(), [&](const PairedArm& a) { return a.scheduler == s; }))
      arms.push_back({s, s, s == o.reference ? ArmRole::kReference : ArmRole::kScheduler, 0});
  }
  if (std::none_of(arms.begin(), arms.end(), [](const PairedArm& a) { return a.role == ArmRole::kReference; }))
    arms.push_back({o.reference, o.reference, ArmRole::kReference, 0});
  arms.push_back({o.reference + " (A/A twin)", o.reference, ArmRole::kTwin, 0});
  arms.push_back({planted_label(o), o.reference, ArmRole::kPlanted, 0});
  return arms;
}

PairedRun run_paired_rounds(const Options& o, Workload& wl, int rank, int ranks, RmaWindow& win,
                            double owner_progress_us) {
  PairedRun run;
  run.arms = paired_arms(o);
  for (std::size_t a = 0; a < run.arms.size(); ++a) {
    if (run.arms[a].role == ArmRole::kReference) run.reference = a;
  }
  // The warm-up: one pass of the reference, which sizes the planted slowdown (rank 0's median frame time).
  {
    set_phase("paired warm-up");
    SchedulerRun warm(o.reference, o, wl, rank, ranks, win, owner_progress_us);
    std::vector<double> frame_s;
    run.ok = warm.run_pass(o.frames, 0.0, frame_s);
    double planted_s = o.planted_pct / 100.0 * median(frame_s);
    MPI_Bcast(&planted_s, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    run.warmup_frame_s = median(frame_s);
    for (PairedArm& arm : run.arms) {
      if (arm.role == ArmRole::kPlanted) arm.planted_s = planted_s;
    }
    SchedulerResult discarded;
    warm.finish(discarded);
  }
  std::vector<std::unique_ptr<SchedulerRun>> runs;
  for (const PairedArm& arm : run.arms)
    runs.push_back(std::make_unique<SchedulerRun>(arm.scheduler, o, wl, rank, ranks, win, owner_progress_us));
  run.rounds.resize(run.arms.size());
  run.results.resize(run.arms.size());
  for (int r = 0; r < o.rounds && run.ok; ++r) {
    const std::vector<std::size_t> order =
        measure::round_order(run.arms.size(), o.seed, static_cast<std::size_t>(r), measure::OrderKind::kRandom);
    for (std::size_t a : order) {
      // The probe on rank 0 just before the arm, while the others wait at the pass's first barrier.
      const double probe = rank == 0 ? noise::probe_ns_per_million_steps() : 0.0;
      note_progress();
      std::vector<double>& frame_s = run.results[a].frame_s;
      const std::size_t before = frame_s.size();
      if (!runs[a]->run_pass(o.frames, run.arms[a].planted_s, frame_s)) {
        run.ok = false;
        break;
      }
      const double t = std::accumulate(frame_s.begin() + static_cast<std::ptrdiff_t>(before), frame_s.end(), 0.0);
      run.rounds[a].add(static_cast<std::size_t>(r), t, probe, 0);
    }
    run.rounds_done = r + 1;
    if (rank == 0 && !o.quiet && run.ok) {
      std::fprintf(stderr, "%s: round %d/%d done (%zu arms in a random order, %d frames each, every frame audited)\n",
                   kProgram.data(), r + 1, o.rounds, run.arms.size(), o.frames);
    }
  }
  for (std::size_t a = 0; a < run.arms.size(); ++a) {
    runs[a]->finish(run.results[a]);
    run.results[a].name = run.arms[a].label;
  }
  return run;
}

std::vector<ArmComparison> compare_arms(const PairedRun& run, double margin_pct) {
  std::vector<ArmComparison> out;
  measure::Settings settings;
  settings.margin = margin_pct / 100.0;
  const measure::ArmRounds& ref = run.rounds[run.reference];
  const double ref_mean =
      ref.size() > 0 ? std::accumulate(ref.time.begin(), ref.time.end(), 0.0) / static_cast<double>(ref.size()) : 0;
  const double frames_per_round =
      run.results[run.reference].frame_s.empty() || ref.size() == 0
          ? 0
          : static_cast<double>(run.results[run.reference].frame_s.size()) / static_cast<double>(ref.size());
  for (std::size_t a = 0; a < run.arms.size(); ++a) {
    if (a == run.reference) continue;
    ArmComparison c;
    c.label = run.arms[a].label;
    c.role = run.arms[a].role;
    c.result = measure::analyze_pairs(measure::pair_rounds(run.rounds[a], ref), settings);
    if (c.role == ArmRole::kPlanted && ref_mean > 0)
      c.planted_pct = 100.0 * run.arms[a].planted_s * frames_per_round / ref_mean;
    out.push_back(std::move(c));
  }
  return out;
}

MethodCheck check_method(const std::vector<ArmComparison>& comparisons) {
  MethodCheck m;
  for (const ArmComparison& c : comparisons) {
    if (c.role == ArmRole::kTwin) {
      m.twin_equivalent = c.result.decision == measure::Decision::kEquivalent;
      m.twin_false_alarm =
          c.result.decision == measure::Decision::kFaster || c.result.decision == measure::Decision::kSlower;
    } else if (c.role == ArmRole::kPlanted) {
      m.planted_found = c.result.decision == measure::Decision::kSlower;
      m.planted_size_held = c.result.chosen().valid && c.result.chosen().contains(std::log1p(c.planted_pct / 100.0));
    }
  }
  return m;
}

}  // namespace frontsteal::mpi
