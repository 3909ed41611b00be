// thread_pinning.hpp — pin a thread to one CPU, and undo it: the main job's --pin.
//
// Pinning takes the OS's migrations out of the measurement (worker w stays on one core, keeps its caches),
// at the price of no escape when another process sits on that core. Off by default: the paper's figures and
// ours are unpinned; --pin shows whether pinning changes the spread of the repeats.
//
// The CPUs are those the process may use when this object is made (sched_getaffinity), so pinning respects
// taskset and cgroup limits; worker w goes to the (w mod count)-th of them.
#pragma once

#include <pthread.h>
#include <sched.h>

#include <vector>

namespace frontsteal {

class ThreadPinning {
 public:
  ThreadPinning() {
    CPU_ZERO(&allowed_);
    if (sched_getaffinity(0, sizeof allowed_, &allowed_) == 0) {
      for (int c = 0; c < CPU_SETSIZE; ++c) {
        if (CPU_ISSET(c, &allowed_)) cpus_.push_back(c);
      }
    }
  }
  // Pins the calling thread to the CPU for worker w; false if the OS refused (or no CPU is known).
  bool pin_this_thread(unsigned w) const {
    if (cpus_.empty()) return false;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpus_[w % cpus_.size()], &one);
    return pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
  }
  // Gives the calling thread every CPU the process had at construction again.
  bool unpin_this_thread() const { return pthread_setaffinity_np(pthread_self(), sizeof allowed_, &allowed_) == 0; }
  std::size_t cpu_count() const noexcept { return cpus_.size(); }
  // The CPU worker w is pinned to (-1 when none is known): where --interference pinned puts its co-runner.
  int cpu_of(unsigned w) const noexcept { return cpus_.empty() ? -1 : cpus_[w % cpus_.size()]; }

 private:
  cpu_set_t allowed_;
  std::vector<int> cpus_;
};

}  // namespace frontsteal
