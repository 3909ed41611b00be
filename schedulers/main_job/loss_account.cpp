// loss_account.cpp — the loss account of a main-job cell (loss_account.hpp).
#include "schedulers/main_job/loss_account.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace frontsteal::main_job {

const char* name(Term t) noexcept {
  switch (t) {
    case Term::kWork: return "work";
    case Term::kClaim: return "claim";
    case Term::kChecks: return "checks";
    case Term::kWake: return "wake";
    case Term::kSearch: return "search";
    case Term::kSteal: return "steal";
    case Term::kWait: return "wait";
    case Term::kTermination: return "termination";
    case Term::kOffCpu: return "off_cpu";
    case Term::kUnaccounted: return "unaccounted";
  }
  return "?";
}

const char* describe(Term t) noexcept {
  switch (t) {
    case Term::kWork: return "work";
    case Term::kClaim: return "claiming items";
    case Term::kChecks: return "the harness's per-item checks";
    case Term::kWake: return "waking the workers";
    case Term::kSearch: return "searching for work";
    case Term::kSteal: return "stealing";
    case Term::kWait: return "waiting on ListTransient";
    case Term::kTermination: return "idle at the frame's end";
    case Term::kOffCpu: return "off the CPU";
    case Term::kUnaccounted: return "unaccounted";
  }
  return "?";
}

void AccountSums::add_frame(const FrameStats& stats, double harness_ns, measure::ItemSamples frame_samples) {
  const double p = static_cast<double>(stats.workers.size());
  const double frame_available = p * harness_ns;
  double measured = 0;
  for (const WorkerFrameStats& w : stats.workers) {
    const auto d = [](std::int64_t v) { return static_cast<double>(v); };
    double between = 0, search = d(w.search_ns);
    if (!stats.phases_timed) {
      // Everything between the worker's first and last claim that is not a claim is the scheduler's claiming;
      // a global queue's lock waits are searching.
      between = std::max(0.0, d(stats.wall_ns) - d(w.wake_ns) - d(w.busy_ns) - d(w.termination_ns));
      search = std::min(between, d(w.lock_wait_ns));
      between -= search;
    }
    wake_ns += d(w.wake_ns);
    busy_ns += d(w.busy_ns);
    search_ns += search;
    steal_ns += d(w.steal_ns);
    wait_ns += d(w.transient_wait_ns);
    termination_ns += d(w.termination_ns);
    between_ns += between;
    active_ns += d(w.active_ns);
    cpu_ns += d(w.cpu_ns);
    off_cpu_ns += std::max(0.0, d(w.active_ns) - d(w.cpu_ns));
    items += d(w.items_processed);
    claims += d(w.claims);
    // The T4 wait is timed inside search, steal or the frame's end (frame_stats.hpp): not a phase of its own.
    measured += d(w.wake_ns) + d(w.busy_ns) + search + d(w.steal_ns) + d(w.termination_ns) + between;
  }
  available_ns += frame_available;
  window_ns += p * static_cast<double>(stats.wall_ns);
  phases_timed = phases_timed || stats.phases_timed;
  ++frames;
  const double open = frame_available > 0 ? std::fabs(frame_available - measured) / frame_available : 0;
  worst_frame_open = std::max(worst_frame_open, open);
  if (open > kClosureBound) ++frames_open;
  samples += frame_samples;
}

LossAccount make_account(const AccountSums& s) {
  LossAccount a;
  a.available_ns = s.available_ns;
  a.checks_per_item_ns = s.samples.checks_per_item_ns();
  a.claim_per_item_ns = s.samples.gap_per_item_ns();
  a.samples = s.samples.items;
  a.gaps = s.samples.gaps_ns.size();
  a.phases_timed = s.phases_timed;
  auto at = [&](Term t) -> double& { return a.ns[static_cast<std::size_t>(t)]; };
  // Busy time: the items (work + the harness's checks) and the claims between items of one claim.
  const double checks = std::min(s.busy_ns, s.items * a.checks_per_item_ns);
  const double per_item_claims = std::min(s.busy_ns - checks, std::max(0.0, s.items - s.claims) * a.claim_per_item_ns);
  at(Term::kChecks) = checks;
  at(Term::kClaim) = per_item_claims + s.between_ns;
  at(Term::kWork) = s.busy_ns - checks - per_item_claims;
  at(Term::kWake) = s.wake_ns;
  // The frame loop times the T4 wait inside search, steal or the frame's end without saying which, so the wait
  // is taken out of those three in proportion to them: the terms still partition the time, none counted twice.
  const double holding = s.search_ns + s.steal_ns + s.termination_ns;
  const double wait = std::min(s.wait_ns, holding);
  const double kept = holding > 0 ? 1 - wait / holding : 1;
  at(Term::kSearch) = s.search_ns * kept;
  at(Term::kSteal) = s.steal_ns * kept;
  at(Term::kWait) = wait;
  at(Term::kTermination) = s.termination_ns * kept;
  double measured = 0;
  for (std::size_t i = 0; i < kTerms; ++i) measured += a.ns[i];
  at(Term::kUnaccounted) = s.available_ns - measured;
  // Off-CPU time out of the terms it fell in, in proportion (wake-up is not part of any worker's active span).
  const Term in_span[] = {Term::kWork,  Term::kClaim, Term::kChecks,     Term::kSearch,
                          Term::kSteal, Term::kWait,  Term::kTermination};
  double span_total = 0;
  for (Term t : in_span) span_total += at(t);
  const double off = span_total > 0 ? std::min(s.off_cpu_ns, span_total) : 0;
  if (off > 0) {
    for (Term t : in_span) at(t) -= off * at(t) / span_total;
    at(Term::kOffCpu) = off;
  }
  return a;
}

}  // namespace frontsteal::main_job
