// openmp-dynamic (schedulers/openmp_scheduler.cpp) keeps one team for the life of an instance, also when teams of
// other sizes run between its frames: the condition under which the main job's rounds, which alternate P, time
// the same OpenMP an application with a fixed team runs. The control shows what the check detects: libgomp ends
// and re-creates the pool's threads when regions of different sizes are opened from one thread.
#include <omp.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <vector>

#include <catch2/catch.hpp>

#include "core/synthetic_work.hpp"
#include "schedulers/library_schedulers.hpp"

namespace fs = frontsteal;
namespace sc = frontsteal::sched;

namespace {

// libgomp is not built for ThreadSanitizer: its barriers are invisible to it, so the TSan build skips these.
bool skipped_under_tsan() {
#if defined(__SANITIZE_THREAD__)
  WARN("libgomp is not instrumented for ThreadSanitizer: checked by the release build");
  return true;
#else
  return false;
#endif
}

long this_thread_tid() { return syscall(SYS_gettid); }

// The kernel thread id of each team member, read by the member itself.
std::vector<long> team_of(sc::Scheduler& s) {
  std::vector<std::atomic<long>> tids(s.worker_count());
  auto item = [&](fs::ItemId, fs::WorkerId w) {
    tids[w].store(this_thread_tid(), std::memory_order_relaxed);
    fs::spin_work(20'000);  // long enough that every member claims an item
  };
  s.run_frame(item);
  std::vector<long> out;
  for (const auto& t : tids) out.push_back(t.load());
  return out;
}

// A raw region of `threads` opened from the calling thread: the ids of its members.
std::vector<long> raw_region(int threads) {
  std::vector<long> tids(static_cast<std::size_t>(threads), 0);
#pragma omp parallel num_threads(threads)
  tids[static_cast<std::size_t>(omp_get_thread_num())] = this_thread_tid();
  return tids;
}

}  // namespace

TEST_CASE("control: regions of another size opened from the same thread end and re-create libgomp's threads",
          "[schedulers][openmp][negative-control]") {
  if (skipped_under_tsan()) return;
  omp_set_dynamic(0);
  const std::vector<long> first = raw_region(3);
  REQUIRE(first[2] != 0);
  (void)raw_region(2);  // the pool's third thread is ended here
  const std::vector<long> again = raw_region(3);
  CHECK(again[1] == first[1]);  // kept
  CHECK(again[2] != first[2]);  // re-created: a new kernel thread
}

TEST_CASE("openmp-dynamic keeps its team across frames when teams of other sizes run between them",
          "[schedulers][openmp]") {
  if (skipped_under_tsan()) return;
  omp_set_dynamic(0);
  auto three = sc::make_openmp_dynamic_scheduler({.workers = 3, .items = 600});
  auto two = sc::make_openmp_dynamic_scheduler({.workers = 2, .items = 600});
  const std::vector<long> first = team_of(*three);
  for (long t : first) REQUIRE(t != 0);
  (void)team_of(*two);
  (void)raw_region(2);  // and a region of the caller's own
  CHECK(team_of(*three) == first);
  CHECK(first[0] != this_thread_tid());  // worker 0 is the instance's driver, not the caller
}
