// rank_watchdog.cpp — the per-rank watchdog (rank_watchdog.hpp).
#include "distributed/rank_watchdog.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "distributed/mpi_options.hpp"
#include "distributed/rank_ledger.hpp"

namespace frontsteal::mpi {
namespace {

using Clock = std::chrono::steady_clock;
std::atomic<std::int64_t> g_last_progress{0};
std::atomic<int> g_frame{-1};
std::atomic<const char*> g_phase{"start"};
std::atomic<bool> g_armed{false};  // armed once the measured part starts (the serial reference may be long)

}  // namespace

void note_progress() noexcept {
  g_last_progress.store(Clock::now().time_since_epoch().count(), std::memory_order_relaxed);
}
void set_phase(const char* phase) noexcept { g_phase.store(phase, std::memory_order_relaxed); }
void set_frame(int frame) noexcept { g_frame.store(frame, std::memory_order_relaxed); }
void arm_watchdog() noexcept {
  note_progress();
  g_armed.store(true);
}

void start_watchdog(double limit_s, int rank) {
  if (limit_s <= 0) return;
  note_progress();
  std::thread([limit_s, rank] {
    while (true) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (!g_armed.load(std::memory_order_relaxed)) continue;
      const auto last = Clock::time_point(Clock::duration(g_last_progress.load(std::memory_order_relaxed)));
      const double idle = std::chrono::duration<double>(Clock::now() - last).count();
      if (idle > limit_s) {
        std::fprintf(stderr,
                     "%s: rank %d: WATCHDOG: no progress for %.1f s (frame %d, %s): a rank died or "
                     "hangs; exiting %d instead of hanging\n",
                     kProgram.data(), rank, idle, g_frame.load(), g_phase.load(), kWatchdogExitCode);
        std::fflush(stderr);
        ledger_exit(LedgerState::kWatchdog);
        std::_Exit(kWatchdogExitCode);
      }
    }
  }).detach();
}

}  // namespace frontsteal::mpi
