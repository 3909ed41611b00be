// os_slowdown.hpp — a fault for the tests: slow this process down by a factor for a while, from outside it, the
// way an overloaded or descheduled node slows a rank. A helper process (fork, no MPI in it) stops this one
// with SIGSTOP and lets it run with SIGCONT in a duty cycle: per period, stopped for (factor - 1) / factor of it,
// running for 1 / factor. A stopped rank makes no MPI call and answers nothing; on one node its window memory
// stays readable and writable by the others (osc/sm), which is what lets rma thieves take its work.
#pragma once

#include <sys/types.h>

#include <chrono>

namespace frontsteal::mpi {

class OsSlowdown {
 public:
  OsSlowdown() = default;
  OsSlowdown(const OsSlowdown&) = delete;
  OsSlowdown& operator=(const OsSlowdown&) = delete;
  ~OsSlowdown() { finish(); }

  // Starts the duty cycle and returns at once (this process keeps running, slowed). Throws std::system_error
  // when the helper cannot be started.
  void start(std::chrono::milliseconds duration, int factor,
             std::chrono::milliseconds period = std::chrono::milliseconds(10));
  // Waits for the helper to end (it always leaves this process running). Idempotent.
  void finish() noexcept;
  bool running() const noexcept { return helper_ > 0; }

 private:
  pid_t helper_ = -1;
};

}  // namespace frontsteal::mpi
