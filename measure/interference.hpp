// interference.hpp — a co-runner: a child process that busy-loops a share (the duty cycle) of one core, so the
// main job can show what another program on the machine does to each scheduler (static lists cannot
// absorb a slowed core; stealing and queues can).
//
// The child is made by fork() without exec: it only makes system calls (prctl, sched_setaffinity,
// clock_gettime, clock_nanosleep, _exit), all async-signal-safe, so forking a process that already runs
// oneTBB or OpenMP threads is safe, and the same code serves the main job and the tests (no executable path
// to find). Each period it spins until duty × period has passed on the monotonic clock, then sleeps to the end
// of the period (duty 100 %: spins without pause). It competes for the CPU like any program: when the OS gives
// it less, it gets less — its real share is read back from /proc/<pid>/stat (cpu_ticks).
//
// It is always reaped:
//   - CoRunner is an RAII guard: its destructor (also on an exception unwinding through it) sends SIGKILL and
//     waits for the child, so no zombie and no stray busy loop remains;
//   - the child sets PR_SET_PDEATHSIG = SIGKILL, so it dies when the thread that forked it dies (the parent
//     killed, std::exit, a crash); it checks getppid() after the prctl for a parent that died before it.
//     start() returns only once the child has armed it (a pipe byte), so a pause() (SIGSTOP) can never
//     freeze the child before it is armed and leave it behind, stopped, when the parent is killed;
//     Fork from a thread that outlives the co-runner (the main thread does).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace frontsteal::interference {

struct CoRunnerOptions {
  double duty = 0.5;       // share of each period spent spinning, (0, 1]
  int period_us = 10'000;  // 10 ms: a scheduler time slice or so, short against a frame
  int cpu = -1;            // pin the child to this CPU (-1: not pinned)
};

class CoRunner {
 public:
  CoRunner() = default;
  // Forks the co-runner; it is running when this returns. Throws std::system_error when fork fails and
  // std::invalid_argument for a duty outside (0, 1] or a period below 100 us.
  static CoRunner start(const CoRunnerOptions& options);

  CoRunner(CoRunner&& other) noexcept : pid_(other.pid_), options_(other.options_) { other.pid_ = -1; }
  CoRunner& operator=(CoRunner&& other) noexcept;
  CoRunner(const CoRunner&) = delete;
  CoRunner& operator=(const CoRunner&) = delete;
  ~CoRunner() { stop(); }

  pid_t pid() const noexcept { return pid_; }
  bool running() const noexcept { return pid_ > 0; }
  const CoRunnerOptions& options() const noexcept { return options_; }

  void pause() const;   // SIGSTOP: takes no CPU until resume()
  void resume() const;  // SIGCONT
  // SIGKILL and wait for it; idempotent, never throws.
  void stop() noexcept;
  // The child's utime + stime so far, in clock ticks (sysconf(_SC_CLK_TCK)); 0 when it is gone.
  std::uint64_t cpu_ticks() const;

 private:
  explicit CoRunner(pid_t pid, const CoRunnerOptions& o) : pid_(pid), options_(o) {}
  pid_t pid_ = -1;
  CoRunnerOptions options_;
};

// utime + stime (fields 14 and 15) of a /proc/<pid>/stat line; nullopt when malformed.
std::optional<std::uint64_t> parse_process_ticks(std::string_view stat_line);
// The same read from /proc/<pid>/stat; 0 when the process does not exist (or pid <= 0).
std::uint64_t process_ticks(pid_t pid);

// --interference DUTY[,pinned|unpinned]: DUTY in % of one core (1 … 100), default set-up unpinned.
struct InterferenceSpec {
  double duty = 0.5;
  bool pinned = false;
  std::string describe() const;  // "50 % of one core, pinned" …
};
// Parses the flag's value; on a bad value returns nullopt and says why in *error.
std::optional<InterferenceSpec> parse_interference(std::string_view value, std::string* error);

}  // namespace frontsteal::interference
