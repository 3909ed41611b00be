// watchdog.hpp — turns a hang into a verdict: no progress for N seconds ends the process with a report.
//
// A protocol bug that keeps a worker inside its frame forever would otherwise surface as a test killed by
// ctest's timeout minutes later, with no word on where the workers stood. The process's watchdog thread
// samples each watched state every 50 ms; while a state is busy (e.g. a frame is in flight) and its progress
// value stays the same for stall_seconds, it prints
//     WATCHDOG: no progress for <X> s in <name>
// followed by the report callback's lines (for StealingWorkers: every worker's Front, End, ListTransient,
// LockList, the active count and the frame counters), flushes stderr and exits with kWatchdogExitCode.
//
// Why "no progress" rather than a total deadline: a run under ThreadSanitizer or on a loaded 2-core machine is
// slow but keeps changing state; a hung one does not. The stall bound can therefore be short (seconds) and
// still never trip a slow but live run. It is scaled up under ThreadSanitizer anyway, and the environment
// variable FRONTSTEAL_WATCHDOG_SECONDS overrides it (e.g. under a debugger).
//
// ROLES
//   owner thread    constructs and destroys a Watchdog (RAII registration with the service).
//   service thread  one per process, started on first use: every 50 ms calls each registered watch's probe()
//                   and, on a stall, its report(); nothing else. Both callbacks must be safe to call from
//                   another thread at any moment while the Watchdog lives: they read shared state through
//                   relaxed atomic loads only (StealingWorkers::debug_state), so they never block on a lock a
//                   stuck worker might hold and never change what they observe.
//
// INVARIANTS
//   WD1  Fires only while probe() reports busy, and only after stall_seconds of the same progress value in
//       consecutive samples; any change restarts the clock. Idle (not busy) time never counts, nor does a
//       pause of the whole process (a gap between samples of half the bound or more restarts the clock).
//       Progress is a claim, a steal or a frame boundary: one item running longer than the bound is a stall.
//   WD2  Firing is deterministic in outcome: the report is written and flushed, then std::_Exit with
//       kWatchdogExitCode (no destructors, no atexit handlers: the other threads are stuck and must not be
//       joined). Tests assert on that exit code and on the "WATCHDOG:" line.
//   WD3  Overhead: registration is a mutex and a vector push; one probe per watch every 50 ms on the service
//       thread; nothing on the watched threads' paths. A process with no watch has no periodic wake-up.
//   WD4  Once ~Watchdog returns, its callbacks are never called again (the service probes under its mutex, and
//       removal takes it), so callbacks may capture references to objects that outlive the Watchdog only.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace frontsteal {

// The exit status of a process a watchdog ended: distinct from a failed check (1), abort (134) and ctest's or
// timeout(1)'s kills, so a test can tell "hung" from "failed".
inline constexpr int kWatchdogExitCode = 86;

#if defined(__SANITIZE_THREAD__)
inline constexpr double kWatchdogSanitizerScale = 4.0;  // TSan runs 5-15x slower; a stall is still a stall
#else
inline constexpr double kWatchdogSanitizerScale = 1.0;
#endif

// The stall bound a watchdog uses unless told otherwise: FRONTSTEAL_WATCHDOG_SECONDS if set (taken as is, not
// scaled), else 10 s (40 s under ThreadSanitizer). Ten seconds without a single claim, steal or frame boundary
// while a frame is in flight is far beyond any item the tests or the stress driver run.
inline double default_watchdog_seconds() {
  if (const char* env = std::getenv("FRONTSTEAL_WATCHDOG_SECONDS")) {
    char* rest = nullptr;
    const double v = std::strtod(env, &rest);
    if (rest != env && v > 0) return v;
  }
  return 10.0 * kWatchdogSanitizerScale;
}

struct WatchdogOptions {
  double stall_seconds = default_watchdog_seconds();
};

// One sample of the watched state.
struct WatchdogSample {
  bool busy = false;           // work is under way, so progress is expected (e.g. a frame is in flight)
  std::uint64_t progress = 0;  // any value that changes while the work advances (a counter, a fingerprint)
};

// An RAII registration with the process's one watchdog thread (WD3): constructing one is a mutex and a vector
// push, not a thread start, so harnesses that run thousands of short scenarios can watch every one of them
// (starting a thread per run measurably slowed them on a loaded 2-core machine).
class Watchdog {
 public:
  using Probe = std::function<WatchdogSample()>;
  using Report = std::function<void(std::FILE*)>;

  Watchdog(std::string name, Probe probe, Report report, WatchdogOptions options = {})
      : name_(std::move(name)), probe_(std::move(probe)), report_(std::move(report)), options_(options) {
    Service::instance().add(this);
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;
  // After this returns the service never calls this watch's probe or report again (WD4).
  ~Watchdog() { Service::instance().remove(this); }

  double stall_seconds() const noexcept { return options_.stall_seconds; }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::milliseconds kPoll{50};

  // The one polling thread, started on first use and joined at static destruction. It holds its mutex while
  // it probes, which is what makes WD4 hold: remove() waits for a probe in progress.
  class Service {
   public:
    static Service& instance() {
      static Service service;
      return service;
    }
    void add(Watchdog* w) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        watches_.push_back(w);
      }
      wake_.notify_all();
    }
    void remove(Watchdog* w) {
      std::lock_guard<std::mutex> lock(mutex_);
      watches_.erase(std::find(watches_.begin(), watches_.end(), w));
    }

   private:
    Service() : thread_([this] { run(); }) {}
    ~Service() {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
      }
      wake_.notify_all();
      thread_.join();
    }
    void run() {
      std::unique_lock<std::mutex> lock(mutex_);
      while (!stop_) {
        if (watches_.empty()) {  // idle: no periodic wake-ups in a process that watches nothing
          wake_.wait(lock, [this] { return stop_ || !watches_.empty(); });
          continue;
        }
        wake_.wait_for(lock, kPoll, [this] { return stop_; });
        const Clock::time_point now = Clock::now();
        for (Watchdog* w : watches_) w->sample(now);
      }
    }
    std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<Watchdog*> watches_;
    bool stop_ = false;
    std::thread thread_;  // last: starts after every other member is initialized
  };

  // Called by the service thread only, under its mutex.
  void sample(Clock::time_point now) {
    const WatchdogSample s = probe_();
    // WD1: a gap between two samples of half the stall bound or more means the whole process (this thread
    // included) was not running — SIGSTOP, CPU throttling, a starved machine. The workers were paused with it,
    // so the gap is not their stall: the clock restarts. (Half the bound, not a few poll periods: on a loaded
    // machine this thread is often late by hundreds of milliseconds, and that must not hide a real hang.)
    const bool paused =
        had_sample_ && std::chrono::duration<double>(now - last_sample_at_).count() >= options_.stall_seconds / 2;
    last_sample_at_ = now;
    if (!s.busy || !had_sample_ || paused || s.progress != last_) {  // WD1: idle, first sample, pause, or progress
      had_sample_ = s.busy;
      last_ = s.progress;
      since_ = now;
      return;
    }
    const double stalled = std::chrono::duration<double>(now - since_).count();
    if (stalled >= options_.stall_seconds) fire(stalled);
  }

  [[noreturn]] void fire(double stalled_seconds) {
    std::fflush(stdout);
    std::fprintf(stderr, "\nWATCHDOG: no progress for %.1f s in %s\n", stalled_seconds, name_.c_str());
    if (report_) report_(stderr);
    std::fprintf(stderr, "WATCHDOG: ending the process (exit code %d) instead of hanging until a timeout\n",
                 kWatchdogExitCode);
    std::fflush(stderr);
    std::_Exit(kWatchdogExitCode);  // WD2
  }

  const std::string name_;
  const Probe probe_;
  const Report report_;
  const WatchdogOptions options_;
  // The service thread's bookkeeping for this watch (only it touches them, under its mutex).
  bool had_sample_ = false;
  std::uint64_t last_ = 0;
  Clock::time_point since_{};
  Clock::time_point last_sample_at_{};  // the service's previous sample of this watch (WD1: pauses)
};

// A watchdog over anything with debug_state() returning a WorkersSnapshot-like value (frame_in_flight(),
// fingerprint(), print(FILE*)): StealingWorkers, StealingScheduler. Busy while a frame is in flight; progress
// is the snapshot's fingerprint, so every claim, steal and frame boundary counts, and a frame in which no
// worker's Front, End, ListTransient or LockList changes for the stall bound is a hang.
template <class Watched>
Watchdog watch_workers(const Watched& watched, std::string name, WatchdogOptions options = {}) {
  return Watchdog(
      std::move(name),
      [&watched] {
        const auto s = watched.debug_state();
        return WatchdogSample{s.frame_in_flight(), s.fingerprint()};
      },
      [&watched](std::FILE* out) { watched.debug_state().print(out); }, options);
}

}  // namespace frontsteal
