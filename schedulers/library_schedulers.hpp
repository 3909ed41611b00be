// library_schedulers.hpp — what a user would pick instead of frontsteal, with the real libraries:
//   oneTBB  tbb::parallel_for over blocked_range(0, N, grain) with one tbb::affinity_partitioner kept across
//           frames, which replays the previous frame's mapping of subranges to threads (the idea of §4.2.1);
//           in a task_arena of P slots (the caller is one of them). Debian libtbb-dev 2021.8.
//   OpenMP  #pragma omp parallel num_threads(P) with schedule(dynamic, grain) (default 1, OpenMP's own
//           default), libgomp from g++ (-fopenmp). The caller is thread 0.
// Both count busy time per claim (per TBB body call; per dynamic chunk). Neither exposes its steals, so
// those counters stay 0. Neither runtime is built with ThreadSanitizer, so the TSan stress tier skips them
// (registry.hpp: SchedulerInfo::tsan_clean).
#pragma once

#include <memory>

#include "schedulers/scheduler.hpp"

namespace frontsteal::sched {

std::unique_ptr<Scheduler> make_tbb_affinity_scheduler(const SchedulerConfig& config);
std::unique_ptr<Scheduler> make_openmp_dynamic_scheduler(const SchedulerConfig& config);

}  // namespace frontsteal::sched
