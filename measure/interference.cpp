// interference.cpp — the co-runner child process and its guard (interference.hpp).
#include "measure/interference.hpp"
#include "measure/proc_file.hpp"

#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <fcntl.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace frontsteal::interference {
namespace {

constexpr long kNsPerS = 1'000'000'000L;

void add_ns(timespec& t, long ns) {
  t.tv_nsec += ns;
  while (t.tv_nsec >= kNsPerS) {
    t.tv_nsec -= kNsPerS;
    ++t.tv_sec;
  }
}
bool before(const timespec& a, const timespec& b) {
  return a.tv_sec < b.tv_sec || (a.tv_sec == b.tv_sec && a.tv_nsec < b.tv_nsec);
}

// The child: system calls only (we are a fork of a multithreaded process; see the header).
// `ready` is the write end of a pipe: one byte written once the death signal is armed, which start() waits
// for (a SIGSTOP from pause() arriving before the prctl would otherwise leave a stopped orphan behind a
// parent killed at that moment).
[[noreturn]] void co_runner_main(pid_t parent, long busy_ns, long period_ns, int cpu, int ready) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(0);  // the parent died before the prctl took effect
  prctl(PR_SET_NAME, "fs-co-runner");
  if (cpu >= 0) {
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    sched_setaffinity(0, sizeof one, &one);
  }
  const char byte = 1;
  while (write(ready, &byte, 1) < 0 && errno == EINTR) {
  }
  close(ready);
  timespec period_start{};
  clock_gettime(CLOCK_MONOTONIC, &period_start);
  volatile std::uint64_t spin = 0;
  for (;;) {
    timespec busy_end = period_start, now{};
    add_ns(busy_end, busy_ns);
    do {
      for (int k = 0; k < 1000; ++k) spin = spin + 1;
      clock_gettime(CLOCK_MONOTONIC, &now);
    } while (before(now, busy_end));
    add_ns(period_start, period_ns);
    if (busy_ns < period_ns) {
      if (before(period_start, now)) period_start = now;  // fell behind (descheduled): start afresh
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &period_start, nullptr);
    } else {
      period_start = now;
    }
  }
}

}  // namespace

CoRunner CoRunner::start(const CoRunnerOptions& o) {
  if (!(o.duty > 0 && o.duty <= 1)) throw std::invalid_argument("co-runner duty must be in (0, 1]");
  if (o.period_us < 100) throw std::invalid_argument("co-runner period must be at least 100 us");
  const long period_ns = 1000L * o.period_us;
  const long busy_ns = std::lround(o.duty * static_cast<double>(period_ns));
  int ready[2];
  if (pipe2(ready, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe for the co-runner");
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    const int e = errno;
    close(ready[0]);
    close(ready[1]);
    throw std::system_error(e, std::generic_category(), "fork of the co-runner");
  }
  if (pid == 0) {
    close(ready[0]);
    co_runner_main(parent, busy_ns, period_ns, o.cpu, ready[1]);
  }
  close(ready[1]);
  CoRunner guard(pid, o);  // from here on, every way out kills and reaps it
  char byte = 0;
  ssize_t got = 0;
  while ((got = read(ready[0], &byte, 1)) < 0 && errno == EINTR) {
  }
  close(ready[0]);
  if (got != 1) throw std::runtime_error("the co-runner died before it started");
  return guard;
}

CoRunner& CoRunner::operator=(CoRunner&& other) noexcept {
  if (this != &other) {
    stop();
    pid_ = other.pid_;
    options_ = other.options_;
    other.pid_ = -1;
  }
  return *this;
}

void CoRunner::pause() const {
  if (pid_ > 0) kill(pid_, SIGSTOP);
}
void CoRunner::resume() const {
  if (pid_ > 0) kill(pid_, SIGCONT);
}

void CoRunner::stop() noexcept {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);  // also ends a stopped child
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
}

std::uint64_t CoRunner::cpu_ticks() const { return process_ticks(pid_); }

std::optional<std::uint64_t> parse_process_ticks(std::string_view line) {
  // "pid (comm) state ppid …": comm may hold spaces and ')', so count fields from the last ')'.
  const auto close = line.rfind(')');
  if (close == std::string_view::npos) return std::nullopt;
  std::istringstream in{std::string(line.substr(close + 1))};
  std::string field;
  std::uint64_t utime = 0, stime = 0;
  for (int i = 3; i <= 15; ++i) {
    if (!(in >> field)) return std::nullopt;
    if (i == 14 || i == 15) {
      std::uint64_t v = 0;
      const auto [p, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
      if (ec != std::errc() || p != field.data() + field.size()) return std::nullopt;
      (i == 14 ? utime : stime) = v;
    }
  }
  return utime + stime;
}

std::uint64_t process_ticks(pid_t pid) {
  if (pid <= 0) return 0;
  return parse_process_ticks(noise::read_proc_file("/proc/" + std::to_string(pid) + "/stat")).value_or(0);
}

std::string InterferenceSpec::describe() const {
  std::ostringstream s;
  s << std::lround(100 * duty) << " % of one core, "
    << (pinned ? "pinned (workers pinned, the co-runner on worker 0's core)" : "unpinned (nothing pinned)");
  return s.str();
}

std::optional<InterferenceSpec> parse_interference(std::string_view value, std::string* error) {
  InterferenceSpec spec;
  std::string_view duty = value, setup;
  if (const auto comma = value.find(','); comma != std::string_view::npos) {
    duty = value.substr(0, comma);
    setup = value.substr(comma + 1);
  }
  auto fail = [&](const std::string& why) -> std::optional<InterferenceSpec> {
    if (error) *error = why;
    return std::nullopt;
  };
  if (!duty.empty()) {
    double pct = 0;
    const auto [p, ec] = std::from_chars(duty.data(), duty.data() + duty.size(), pct);
    if (ec != std::errc() || p != duty.data() + duty.size() || !(pct >= 1 && pct <= 100)) {
      return fail("duty '" + std::string(duty) + "' is not a percentage of one core from 1 to 100");
    }
    spec.duty = pct / 100.0;
  }
  if (setup == "pinned") {
    spec.pinned = true;
  } else if (!setup.empty() && setup != "unpinned") {
    return fail("set-up '" + std::string(setup) + "' is neither pinned nor unpinned");
  }
  return spec;
}

}  // namespace frontsteal::interference
