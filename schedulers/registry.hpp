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
//   openmp-dynamic        OpenMP schedule(dynamic)                                    busy
// Not in this table (another process, another OpenMP runtime): openmp-static-steal, LLVM libomp's
// static_steal, run by the main job as a child process (schedulers/llvm_openmp/, llvm_openmp_child.hpp).
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
};

// Every scheduler this build can run (stealing/Asymmetric only where membarrier is available), in table order.
const std::vector<SchedulerInfo>& scheduler_registry();

// The entry called `name`, or nullptr.
const SchedulerInfo* find_scheduler(const std::string& name);

}  // namespace frontsteal::sched
