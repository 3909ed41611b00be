// The loss account's phase times from the stealing protocol (core/phase_timer.hpp, core/frame_loop.hpp,
// core/frame_stats.hpp): a frame in which one worker must steal fills wake-up, busy, search, steal and
// termination so that they cover the worker's part of the caller's window, with little left between them; the
// T4 wait is reported to the observer around a real wait; NoPhaseTimer leaves the thief's phases at 0.
#include "core/phase_timer.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

#include "core/frame_loop.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/synthetic_work.hpp"

namespace fs = frontsteal;
using fs::ItemId;
using fs::WorkerId;

namespace {

// Worker 0's block (the first half) is costly and worker 1's free, so worker 1 runs out at once and steals. Worker
// 0's first item holds on until worker 1 has run one of worker 0's items (bounded by 10 s), so the frame has a
// successful steal by worker 1 however late a loaded machine starts that thread.
template <class Timer>
fs::FrameStats one_frame_with_steals(ItemId n) {
  fs::StealingScheduler<fs::Fenced, fs::StdBackend, Timer> s({.workers = 2, .items = n, .seed = 3});
  std::atomic<bool> worker_1_stole{false};
  auto item = [n, &worker_1_stole](ItemId id, WorkerId w) {
    if (id >= n / 2) return;
    if (w == 1) worker_1_stole.store(true);
    if (id == 0) {
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (!worker_1_stole.load() && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    }
    fs::spin_work(20000);
  };
  return s.run_frame(item);
}

// A thief's observer that records what try_steal told it.
struct RecordingObserver {
  int locks = 0, waits_over = 0;
  std::atomic<int> waits_begun{0};
  std::chrono::steady_clock::time_point wait_start{}, wait_end{};
  void locked() noexcept { ++locks; }
  void wait_begins() noexcept {
    wait_start = std::chrono::steady_clock::now();
    ++waits_begun;
  }
  void wait_over() noexcept {
    ++waits_over;
    wait_end = std::chrono::steady_clock::now();
  }
};

}  // namespace

TEST_CASE("a frame's phase times cover every worker's part of the caller's window", "[core][account]") {
  const fs::FrameStats st = one_frame_with_steals<fs::SteadyPhaseTimer>(400);
  CHECK(st.phases_timed);
  REQUIRE(st.workers.size() == 2);
  CHECK(st.totals().steals_succeeded >= 1);
  CHECK(st.workers[1].steal_ns > 0);  // worker 1 stole at least once
  for (const fs::WorkerFrameStats& w : st.workers) {
    CAPTURE(w.wake_ns, w.busy_ns, w.search_ns, w.steal_ns, w.transient_wait_ns, w.termination_ns, st.wall_ns);
    CHECK(w.wake_ns >= 0);
    CHECK(w.termination_ns >= 0);
    CHECK(w.search_ns >= 0);
    CHECK(w.claims >= 1);
    // The T4 wait is inside search or steal, not a phase of its own.
    CHECK(w.transient_wait_ns <= w.search_ns + w.steal_ns + w.termination_ns);
    const std::int64_t covered = w.wake_ns + w.busy_ns + w.search_ns + w.steal_ns + w.termination_ns;
    CHECK(covered <= st.wall_ns);
    // What no phase claims is the code between them (a few list operations): far below a tenth of the frame.
    CHECK(covered >= st.wall_ns - st.wall_ns / 10);
  }
}

TEST_CASE("without a phase timer the thief's phases are 0 and wake-up and termination remain", "[core][account]") {
  const fs::FrameStats st = one_frame_with_steals<fs::NoPhaseTimer>(400);
  CHECK_FALSE(st.phases_timed);
  CHECK(st.totals().steals_succeeded >= 1);
  CHECK(st.totals().search_ns == 0);
  CHECK(st.totals().steal_ns == 0);
  CHECK(st.totals().transient_wait_ns == 0);
  CHECK(st.totals().termination_ns > 0);  // from the clock reads the busy time makes anyway
}

TEST_CASE("try_steal tells its observer when it holds the LockList and how long it waited at T4", "[core][account]") {
  fs::StealingWorkers<fs::StdBackend, fs::Fenced> core(2, 64, 1);
  auto& owner = core.owner(0);
  owner.announce();  // O1: the owner is inside a claim, ListTransient raised
  RecordingObserver seen;
  std::atomic<bool> done{false};
  fs::StealOutcome outcome = fs::StealOutcome::kEmpty;
  std::thread thief([&] {
    outcome = core.thief(1).try_steal(core.slot(0), seen);
    done = true;
  });
  // The thief waits at T4 (the test waits for it to get there, as long as a loaded machine takes), then 20 ms.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (seen.waits_begun.load() == 0 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
  REQUIRE(seen.waits_begun.load() == 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK_FALSE(done.load());
  const auto released = std::chrono::steady_clock::now();
  owner.storeload_fence();
  (void)owner.finish_claim(owner.read_end());  // O2-O4: the claim ends, ListTransient falls
  thief.join();
  CHECK(outcome == fs::StealOutcome::kStolen);
  CHECK(seen.locks == 1);
  CHECK(seen.waits_begun == 1);
  CHECK(seen.waits_over == 1);
  CHECK(seen.wait_end >= released);
  CHECK(seen.wait_end - seen.wait_start >= std::chrono::milliseconds(15));
}
