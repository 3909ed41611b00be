// registry.hpp — every scheduler by name, behind the one interface (scheduler.hpp).
//
//   name                  what                                                     per-frame counters
//   round-robin           static: item i on worker i mod P (§3)                     busy
//   spatial-annealing     static: the paper's graph partition, simulated annealing  busy
//   spatial-morton        static: Morton order of patch centres, dealt round robin   busy
//   queue-mutex           global queue under std::mutex, grain N/(100P) (§4.1)       busy, lock waits
//   moodycamel-queue      lock-free queue (moodycamel::ConcurrentQueue), N/(100P)     busy
//   counter-atomic        one atomic fetch_add per claim, grain N/(100P)             busy
//   stealing/<Policy>     the core protocol (§4.2), per memory-order policy          busy, steals
//   chase-lev             Chase–Lev deques (Lê et al. orders), binary range split    busy, steals
//   tbb-affinity          oneTBB parallel_for + affinity_partitioner                 busy
//   openmp-dynamic        OpenMP schedule(dynamic), chunk N/(100P) as the global queue  busy
// Not in this table (another process, another OpenMP runtime): openmp-static-steal, LLVM libomp's
// static_steal, run by the main job as a child process (schedulers/llvm_openmp/, llvm_openmp_child.hpp).
//
// Variants (SchedulerInfo::variant, never in `all`):
//   stealing/Fenced:caller-works      the calling thread runs worker 0's part of each frame (core/
//                                     stealing_scheduler.hpp: tried, equivalent, not the default)
//   openmp-dynamic:chunk1             OpenMP's default chunk: every claim a fetch_add on the team's shared
//                                     counter (~0.2 us per item at P = 2 here: the line moves between cores)
//   stealing/Fenced:no-account        no loss account: no phase timer (core/phase_timer.hpp), and the main job
//                                     samples none of its items (measure/item_sampler.hpp): what the account costs
//
// Static spatial schedulers use WorkloadHints (centres, estimated costs); the others ignore it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/policies.hpp"
#include "schedulers/scheduler.hpp"

namespace frontsteal::sched {

struct SchedulerInfo {
  std::string name;
  std::string summary;
  Contract contract = Contract::kExactlyOnce;  // at-least-once: stealing/Paper only
  bool tsan_clean = true;                      // false: its runtime is not built with ThreadSanitizer (TBB, OpenMP)
  std::function<std::unique_ptr<Scheduler>(const SchedulerConfig&, const WorkloadHints&)> make;
  // A variant of another entry, named "<entry>:<what differs>", for measuring one design choice against it (the
  // main job's --schedulers; `all` leaves variants out): the previous design of a lever that was kept, or the
  // account's counters switched off.
  bool variant = false;
  // Its workers' thread CPU time is measured (false: oneTBB, whose threads join the arena per claim, where the
  // system-call clock around every claim cost more than the claims; cpu_ns is then active_ns).
  bool cpu_time = true;
  // The loss account is taken for it (the harness samples its items; its phases are timed where it has any).
  // false: the variant that measures what the account costs (stealing/Fenced:no-account).
  bool account = true;
};

// Every scheduler this build can run (stealing/Asymmetric only where membarrier is available), in table order.
const std::vector<SchedulerInfo>& scheduler_registry();

// The entry called `name`, or nullptr.
const SchedulerInfo* find_scheduler(const std::string& name);

}  // namespace frontsteal::sched
