// registry.cpp — the table of registry.hpp.
#include "schedulers/registry.hpp"

#include "core/membarrier.hpp"
#include "schedulers/chase_lev_scheduler.hpp"
#include "schedulers/chunked_counter_scheduler.hpp"
#include "schedulers/concurrent_queue_scheduler.hpp"
#include "schedulers/global_queue_scheduler.hpp"
#include "schedulers/library_schedulers.hpp"
#include "schedulers/static_assignment.hpp"
#include "schedulers/static_scheduler.hpp"
#include "schedulers/stealing_adapter.hpp"

namespace frontsteal::sched {
namespace {

template <class Policy>
SchedulerInfo stealing_entry() {
  return {"stealing/" + std::string(Policy::kName), "load stealing (paper §4.2), policy " + std::string(Policy::kName),
          Policy::kContract, true, [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
            return std::make_unique<StealingAdapter<Policy>>(c);
          }};
}

// A variant of stealing/<Policy> (registry.hpp lists them).
template <class Policy, class Timer>
SchedulerInfo stealing_variant(const std::string& suffix, const std::string& what, bool caller_works) {
  SchedulerInfo info{"stealing/" + std::string(Policy::kName) + ":" + suffix,
                     "variant of stealing/" + std::string(Policy::kName) + ": " + what, Policy::kContract, true,
                     [caller_works](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                       return std::make_unique<StealingAdapter<Policy, Timer>>(c, caller_works);
                     }};
  info.variant = true;
  return info;
}

std::vector<SchedulerInfo> build() {
  std::vector<SchedulerInfo> all;
  all.push_back({"round-robin", "static, item i on worker i mod P (paper §3)", Contract::kExactlyOnce, true,
                 [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<StaticScheduler>(c, round_robin_assignment(c.items, c.workers));
                 }});
  all.push_back({"spatial-annealing", "static, graph partition by simulated annealing (paper §3)",
                 Contract::kExactlyOnce, true,
                 [](const SchedulerConfig& c, const WorkloadHints& h) -> std::unique_ptr<Scheduler> {
                   AnnealingOptions o;
                   o.seed = c.seed;
                   return std::make_unique<StaticScheduler>(c, annealed_assignment(c.items, c.workers, h, o));
                 }});
  all.push_back({"spatial-morton", "static, Morton order of patch centres dealt round robin", Contract::kExactlyOnce,
                 true, [](const SchedulerConfig& c, const WorkloadHints& h) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<StaticScheduler>(c, morton_deal_assignment(c.items, c.workers, h));
                 }});
  all.push_back({"queue-mutex", "global queue under std::mutex, grain N/(100P) (paper §4.1)", Contract::kExactlyOnce,
                 true, [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<GlobalQueueScheduler>(c);
                 }});
  all.push_back({"moodycamel-queue", "lock-free global queue (moodycamel::ConcurrentQueue), grain N/(100P)",
                 Contract::kExactlyOnce, true,
                 [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<ConcurrentQueueScheduler>(c);
                 }});
  all.push_back({"counter-atomic", "chunked atomic counter, grain N/(100P)", Contract::kExactlyOnce, true,
                 [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<ChunkedCounterScheduler>(c);
                 }});
  all.push_back(stealing_entry<SeqCst>());
  all.push_back(stealing_entry<Fenced>());
  all.push_back(stealing_entry<Minimal>());
  if (membarrier_status().available) all.push_back(stealing_entry<Asymmetric>());
  all.push_back(stealing_entry<Paper>());
  all.push_back(stealing_variant<Fenced, SteadyPhaseTimer>(
      "caller-works", "the calling thread runs worker 0's part of each frame", true));
  SchedulerInfo unaccounted = stealing_variant<Fenced, NoPhaseTimer>(
      "no-account", "no loss account (phase timer off, items not sampled)", false);
  unaccounted.account = false;
  all.push_back(std::move(unaccounted));
  all.push_back({"chase-lev", "Chase-Lev deques (Le et al. PPoPP'13 orders), binary range splitting",
                 Contract::kExactlyOnce, true,
                 [](const SchedulerConfig& c, const WorkloadHints&) -> std::unique_ptr<Scheduler> {
                   return std::make_unique<ChaseLevScheduler>(c);
                 }});
  SchedulerInfo tbb{"tbb-affinity", "oneTBB parallel_for with affinity_partitioner", Contract::kExactlyOnce, false,
                    [](const SchedulerConfig& c, const WorkloadHints&) { return make_tbb_affinity_scheduler(c); }};
  tbb.cpu_time = false;
  all.push_back(std::move(tbb));
  all.push_back({"openmp-dynamic", "OpenMP schedule(dynamic), chunk N/(100P)", Contract::kExactlyOnce, false,
                 [](const SchedulerConfig& c, const WorkloadHints&) { return make_openmp_dynamic_scheduler(c); }});
  SchedulerInfo omp_chunk1{"openmp-dynamic:chunk1", "variant of openmp-dynamic: chunk 1 (OpenMP's default)",
                           Contract::kExactlyOnce, false, [](const SchedulerConfig& c, const WorkloadHints&) {
                             SchedulerConfig one = c;
                             if (one.grain == 0) one.grain = 1;
                             return make_openmp_dynamic_scheduler(one);
                           }};
  omp_chunk1.variant = true;
  all.push_back(std::move(omp_chunk1));
  return all;
}

}  // namespace

const std::vector<SchedulerInfo>& scheduler_registry() {
  static const std::vector<SchedulerInfo> all = build();
  return all;
}

const SchedulerInfo* find_scheduler(const std::string& name) {
  for (const auto& s : scheduler_registry()) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

}  // namespace frontsteal::sched
