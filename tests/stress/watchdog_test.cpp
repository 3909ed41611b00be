// stress/watchdog.hpp: what must NOT fire. Firing itself (exit code 86 and the per-worker report) is checked by
// the ctest watchdog.catches_planted_hang, in a child process, since it ends the process.
#include "stress/watchdog.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>

namespace fs = frontsteal;

namespace {

// Runs for `seconds` under a watchdog with the given stall bound whose probe reports `busy` and `progress`.
// Surviving is the assertion: a false alarm would end the test binary with exit code 86.
template <class Busy, class Progress>
void survive(double seconds, double stall_seconds, Busy busy, Progress progress) {
  fs::WatchdogOptions options;
  options.stall_seconds = stall_seconds;
  const fs::Watchdog dog(
      "stress_watchdog_test",
      [&] {
        return fs::WatchdogSample{busy(), progress()};
      },
      [](std::FILE* out) { std::fprintf(out, "  (test probe)\n"); }, options);
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

}  // namespace

TEST_CASE("a watchdog never fires while the watched state is idle", "[core][watchdog]") {
  survive(
      0.6, 0.2, [] { return false; }, [] { return std::uint64_t{0}; });  // no frame in flight: nothing expected
  SUCCEED("idle for 3x the stall bound without firing");
}

TEST_CASE("a watchdog never fires while busy work keeps progressing", "[core][watchdog]") {
  std::atomic<std::uint64_t> counter{0};
  std::atomic<bool> stop{false};
  std::thread worker([&] {
    while (!stop.load(std::memory_order::relaxed)) {
      counter.fetch_add(1, std::memory_order::relaxed);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // slow, but well inside the bound
    }
  });
  // A 1 s bound: a loaded machine (or TSan) can keep a sleeping thread from running for a few hundred ms while
  // the watchdog's own samples stay regular, which a 0.2 s bound would call a stall.
  survive(
      2.0, 1.0, [] { return true; }, [&] { return counter.load(std::memory_order::relaxed); });
  stop.store(true, std::memory_order::relaxed);
  worker.join();
  SUCCEED("busy for 2x the stall bound, progressing, without firing");
}

TEST_CASE("watchdogs come and go cheaply: one service thread, not one thread each", "[core][watchdog]") {
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 10000; ++i) {
    const fs::Watchdog dog("stress_watchdog_test", [] { return fs::WatchdogSample{true, 0}; }, {});
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  INFO(seconds << " s for 10000 registrations");
  CHECK(seconds < 5.0);  // about 1 us each on an idle machine; the bound only rules out a thread per watch
}

TEST_CASE("the stall bound scales under ThreadSanitizer and is overridable", "[core][watchdog]") {
  CHECK(fs::kWatchdogSanitizerScale >= 1.0);
  fs::WatchdogOptions options;
  CHECK(options.stall_seconds == fs::default_watchdog_seconds());
  CHECK(fs::default_watchdog_seconds() > 0);
}
