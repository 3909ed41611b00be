// interference_test.cpp — the co-runner child (measure/interference.hpp) is always reaped: after the
// guard's scope, on an exception unwinding through it, and when moved; the flag parser's bad values; the
// noise monitor counts the co-runner as ours, not as another process. No timing assertions: the child's
// CPU time is only required to be readable, not to reach its duty.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>

#include "measure/interference.hpp"
#include "measure/noise_monitor.hpp"

namespace fi = frontsteal::interference;
namespace nz = frontsteal::noise;

namespace {

// Gone: no process (not even a zombie) has this pid as our child. waitpid on an already reaped pid fails
// with ECHILD; kill(pid, 0) then fails with ESRCH (pids are not reused this quickly on a test machine; the
// ECHILD check alone already proves we left no zombie of ours).
bool gone(pid_t pid) {
  errno = 0;
  const bool no_child = waitpid(pid, nullptr, WNOHANG) < 0 && errno == ECHILD;
  errno = 0;
  const bool no_process = kill(pid, 0) < 0 && errno == ESRCH;
  return no_child && no_process;
}

}  // namespace

TEST_CASE("co-runner runs inside the guard and is reaped at the end of its scope", "[interference]") {
  pid_t pid = -1;
  {
    fi::CoRunner c = fi::CoRunner::start({.duty = 0.5, .period_us = 5000});
    pid = c.pid();
    REQUIRE(pid > 0);
    CHECK(kill(pid, 0) == 0);
    c.pause();
    c.resume();
    // /proc/<pid>/stat is readable while it runs (its tick count may still be 0).
    CHECK(fi::parse_process_ticks("1 (x) R 1 1 1 0 -1 0 0 0 0 0 7 5 0 0") == 12u);
    (void)c.cpu_ticks();
  }
  CHECK(gone(pid));
}

TEST_CASE("co-runner is reaped when an exception unwinds through its guard", "[interference]") {
  pid_t pid = -1;
  auto run = [&] {
    fi::CoRunner c = fi::CoRunner::start({.duty = 1.0, .period_us = 1000});
    pid = c.pid();
    c.pause();  // stopped children must be reaped too
    throw std::runtime_error("a measurement failed mid-run");
  };
  CHECK_THROWS_AS(run(), std::runtime_error);
  REQUIRE(pid > 0);
  CHECK(gone(pid));
}

TEST_CASE("co-runner moved into another guard is reaped once, by the last owner", "[interference]") {
  pid_t pid = -1;
  {
    fi::CoRunner outer;
    {
      fi::CoRunner inner = fi::CoRunner::start({});
      pid = inner.pid();
      outer = std::move(inner);
      CHECK_FALSE(inner.running());  // NOLINT(bugprone-use-after-move): the moved-from state is what is tested
    }
    CHECK(kill(pid, 0) == 0);  // the moved-from guard did not kill it
    outer.stop();
    CHECK(gone(pid));
    outer.stop();  // idempotent
  }
  CHECK(gone(pid));
}

TEST_CASE("co-runner options out of range are refused without forking", "[interference]") {
  CHECK_THROWS_AS(fi::CoRunner::start({.duty = 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(fi::CoRunner::start({.duty = 1.5}), std::invalid_argument);
  CHECK_THROWS_AS(fi::CoRunner::start({.duty = 0.5, .period_us = 10}), std::invalid_argument);
}

TEST_CASE("parse_interference reads DUTY and the set-up", "[interference]") {
  std::string why;
  auto s = fi::parse_interference("50", &why);
  REQUIRE(s);
  CHECK(s->duty == Approx(0.5));
  CHECK_FALSE(s->pinned);
  s = fi::parse_interference("30,pinned", &why);
  REQUIRE(s);
  CHECK(s->duty == Approx(0.3));
  CHECK(s->pinned);
  s = fi::parse_interference(",unpinned", &why);
  REQUIRE(s);
  CHECK(s->duty == Approx(0.5));
  CHECK_FALSE(fi::parse_interference("0", &why));
  CHECK_FALSE(fi::parse_interference("101", &why));
  CHECK_FALSE(fi::parse_interference("50,sideways", &why));
  CHECK(why.find("sideways") != std::string::npos);
  CHECK_FALSE(fi::parse_interference("half", &why));
}

TEST_CASE("noise monitor leaves the known co-runner out of other processes but counts the rest", "[interference]") {
  // Synthetic windows: 1000 ticks, 300 busy of which 100 ours and 150 the co-runner's -> others 50 (5 %).
  nz::Usage u;
  u.total_ticks = 1000;
  u.busy_ticks = 300;
  u.self_ticks = 100;
  u.known_ticks = 150;
  CHECK(u.other_ticks() == 50u);
  CHECK(u.known_share() == Approx(0.15));
  CHECK_FALSE(nz::assess(u, nz::Thresholds{}).busy);
  // Without knowing the co-runner, the same window is busy: the negative control of the subtraction.
  nz::Usage unknown = u;
  unknown.known_ticks = 0;
  CHECK(nz::assess(unknown, nz::Thresholds{}).busy);
  // Genuinely external load beside the co-runner is still flagged.
  nz::Usage loaded = u;
  loaded.busy_ticks = 600;
  CHECK(nz::assess(loaded, nz::Thresholds{}).busy);
  // A co-runner reaped between two samples reads 0 afterwards: the window counts 0 for it, never wraps.
  nz::ProcSample a, b;
  a.ok = b.ok = true;
  a.total_ticks = 100;
  b.total_ticks = 200;
  a.known_ticks = 40;
  b.known_ticks = 0;
  CHECK(nz::usage_between(a, b).known_ticks == 0u);
}
