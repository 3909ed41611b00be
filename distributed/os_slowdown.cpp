// os_slowdown.cpp — OsSlowdown (os_slowdown.hpp).
#include "distributed/os_slowdown.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace frontsteal::mpi {
namespace {

void sleep_ns(long long ns) {
  timespec t{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  while (nanosleep(&t, &t) != 0 && errno == EINTR) {
  }
}

long long monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<long long>(t.tv_sec) * 1000000000 + t.tv_nsec;
}

}  // namespace

void OsSlowdown::start(std::chrono::milliseconds duration, int factor, std::chrono::milliseconds period) {
  finish();
  const pid_t target = getpid();
  const long long period_ns = std::chrono::nanoseconds(period).count();
  const long long running_ns = period_ns / (factor > 1 ? factor : 1);
  const long long until = monotonic_ns() + std::chrono::nanoseconds(duration).count();
  const pid_t child = fork();
  if (child < 0) throw std::system_error(errno, std::generic_category(), "--slow: fork");
  if (child == 0) {  // the helper: async-signal-safe calls only, no MPI, no allocation
    while (monotonic_ns() < until) {
      kill(target, SIGSTOP);
      sleep_ns(period_ns - running_ns);
      kill(target, SIGCONT);
      sleep_ns(running_ns);
    }
    kill(target, SIGCONT);
    _exit(0);
  }
  helper_ = child;
}

void OsSlowdown::finish() noexcept {
  if (helper_ <= 0) return;
  int status = 0;
  while (waitpid(helper_, &status, 0) < 0 && errno == EINTR) {
  }
  helper_ = -1;
}

}  // namespace frontsteal::mpi
