// cpu_speed_probe_test.cpp — the CPU speed probe (measure/cpu_speed_probe.hpp): the diagnosis on synthetic
// repeats (the machine slowed down; the program varied on a steady core; a quiet run; nothing measured), and
// the probe itself: it really runs its chain (a chain the compiler dropped would take ~0 ns), and it measures
// the wall time of that chain, lost CPU included (a probe stopped mid-run by SIGSTOP for 300 ms must report at
// least that). Both probe checks hold on a loaded machine: load only makes the probe slower.
#include "measure/cpu_speed_probe.hpp"

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <thread>

namespace nz = frontsteal::noise;

TEST_CASE("probe spread with the serial spread: the machine changed speed", "[cpu_probe]") {
  // The 16-vCPU VM of the 16-core study: bimodal passes; a probe that follows them.
  const std::vector<double> serial{905, 1374, 982, 859, 1415};
  const std::vector<double> probe{2.0e6, 3.05e6, 2.15e6, 1.95e6, 3.1e6};
  const nz::SpreadDiagnosis d = nz::diagnose_spread(serial, probe, 0.05);
  CHECK(d.cpu_varied);
  CHECK(d.probe_follows_passes);
  CHECK(d.serial_spread == Approx(1415.0 / 859 - 1));
  CHECK(d.probe_spread == Approx(3.1 / 1.95 - 1));
  CHECK(d.correlation > 0.95);
  CHECK(d.line.find("the CPU itself changed speed") != std::string::npos);
}

TEST_CASE("one probe inflated by a lost time slice, uncorrelated with the passes: not the core's speed",
          "[cpu_probe]") {
  const std::vector<double> serial{905, 1374, 982, 859, 1415};
  const std::vector<double> probe{2.04e6, 2.05e6, 6.1e6, 2.06e6, 2.04e6};  // the third: preempted, not slower
  const nz::SpreadDiagnosis d = nz::diagnose_spread(serial, probe, 0.05);
  CHECK(d.cpu_varied);
  CHECK(d.correlation < 0.7);
  CHECK_FALSE(d.probe_follows_passes);
  CHECK(d.line.find("the CPU itself changed speed") == std::string::npos);
}

TEST_CASE("a steady probe beside a spread serial loop: not the core's clock", "[cpu_probe]") {
  const std::vector<double> serial{905, 1374, 982, 859, 1415};
  const std::vector<double> probe{2.04e6, 2.05e6, 2.03e6, 2.06e6, 2.04e6};
  const nz::SpreadDiagnosis d = nz::diagnose_spread(serial, probe, 0.05);
  CHECK_FALSE(d.cpu_varied);
  CHECK(d.line.find("did not change") != std::string::npos);
  CHECK(d.line.find("memory, caches, the program or time off the CPU") != std::string::npos);
}

TEST_CASE("a probe that moved less than the serial loop: part machine, part not", "[cpu_probe]") {
  // A 2-vCPU VM, README command 1: passes drifting 498 ... 632 ms, the probe 1.96 ... 2.09 ms.
  const std::vector<double> serial{511, 498, 531, 556, 533, 557, 555, 610, 632, 581};
  const std::vector<double> probe{1.974e6, 1.956e6, 2.055e6, 2.088e6, 1.980e6,
                                  2.084e6, 2.055e6, 2.054e6, 2.086e6, 2.086e6};
  const nz::SpreadDiagnosis d = nz::diagnose_spread(serial, probe, 0.05);
  CHECK(d.cpu_varied);
  CHECK(d.correlation > 0.5);
  CHECK_FALSE(d.probe_follows_passes);
  CHECK(d.line.find("does not explain the serial loop's") != std::string::npos);
}

TEST_CASE("the same user-mode work in every pass, a steady probe: still the machine", "[cpu_probe]") {
  // A 2-vCPU VM, measured: no fault, no system time, never blocked, and one pass 18 % slower.
  const std::vector<double> serial{523, 517, 614, 538, 527};
  const std::vector<double> probe{2.04e6, 2.05e6, 2.06e6, 2.04e6, 2.05e6};
  std::vector<nz::PassUsage> passes;
  for (double ms : serial) passes.push_back({.wall_ms = ms, .user_ms = ms - 2, .involuntary_switches = 4});
  // A pass that lost 5 % of its wall time off the CPU is not "the same work on its CPU" either.
  {
    std::vector<nz::PassUsage> preempted = passes;
    preempted[1].user_ms = 0.95 * preempted[1].wall_ms;
    CHECK_FALSE(nz::diagnose_spread(serial, probe, 0.05, preempted).same_work_on_cpu);
  }
  const nz::SpreadDiagnosis same_work = nz::diagnose_spread(serial, probe, 0.05, passes);
  CHECK(same_work.same_work_on_cpu);
  CHECK_FALSE(same_work.probe_follows_passes);
  CHECK(same_work.line.find("did the same work on its CPU") != std::string::npos);
  CHECK(same_work.line.find("not different work by the program") != std::string::npos);
  // Negative control: one pass took page faults (the program touched new memory) — then it is not the machine's.
  passes[2].faults = 1200;
  const nz::SpreadDiagnosis faulted = nz::diagnose_spread(serial, probe, 0.05, passes);
  CHECK_FALSE(faulted.same_work_on_cpu);
  CHECK(faulted.line.find("1200 page faults") != std::string::npos);
}

TEST_CASE("a pass's own thread: page faults and blocking are seen, pure arithmetic is user mode only", "[cpu_probe]") {
  {  // pure arithmetic: no fault, never blocked (once its code and stack pages are in: run it once first)
    nz::probe_ns_per_million_steps(1000);
    const nz::PassMeter meter;
    nz::probe_ns_per_million_steps(2'000'000);
    const nz::PassUsage u = meter.stop();
    CHECK(u.faults == 0);
    CHECK(u.voluntary_switches == 0);
    CHECK(u.wall_ms > 0);
  }
  {  // 4 MiB of fresh anonymous memory, every page touched: a fault per page at least once
    constexpr std::size_t kBytes = 4u << 20;
    void* p = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    REQUIRE(p != MAP_FAILED);
    const nz::PassMeter meter;
    for (std::size_t i = 0; i < kBytes; i += 4096) static_cast<volatile char*>(p)[i] = 1;
    const nz::PassUsage u = meter.stop();
    munmap(p, kBytes);
    CHECK(u.faults >= 1);
    CHECK_FALSE(nz::same_work_on_cpu({u}));
  }
  {  // a sleep blocks
    const nz::PassMeter meter;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const nz::PassUsage u = meter.stop();
    CHECK(u.voluntary_switches >= 1);
    CHECK_FALSE(nz::same_work_on_cpu({u}));
  }
  CHECK_FALSE(nz::same_work_on_cpu({}));
}

TEST_CASE("a quiet run only reports the probe", "[cpu_probe]") {
  const std::vector<double> serial{517, 522, 507, 522, 524};
  const std::vector<double> probe{2.04e6, 2.07e6, 2.03e6, 2.00e6, 2.02e6};
  const nz::SpreadDiagnosis d = nz::diagnose_spread(serial, probe, 0.05);
  CHECK_FALSE(d.cpu_varied);
  CHECK(d.line.rfind("CPU speed probe: ", 0) == 0);
}

TEST_CASE("no probe values: said, no verdict", "[cpu_probe]") {
  const nz::SpreadDiagnosis d = nz::diagnose_spread({900, 1400}, {}, 0.05);
  CHECK_FALSE(d.cpu_varied);
  CHECK(d.line == "CPU speed probe: not measured");
  CHECK(nz::diagnose_spread({900, 1400}, {2e6}, 0.05).line == "CPU speed probe: not measured");
}

TEST_CASE("the probe runs its chain: no faster than 0.2 ns per dependent step", "[cpu_probe]") {
  // Eight multiply-adds and eight shift-xors per step: no core retires eight multiplies in under a cycle, and
  // no core runs above 5 GHz. A chain the compiler removed would report close to 0.
  const double ns = nz::probe_ns_per_million_steps(2'000'000);
  CHECK(ns > 0.2e6);
  CHECK(ns < 1e9);  // and it ends: under 1 us per step even on a loaded machine
}

// One try. A child runs one long probe (kLongProbeSteps, ~100 ms of CPU on an idle core) and writes its result.
// The stop must land inside that probe, so the parent waits until the child has used 10 ms of CPU (the child does
// nothing else before the probe, and the probe needs far more), stops it, waits until the kernel reports it
// stopped, sleeps 300 ms by its own clock, and resumes it. Signalling the moment a short probe ends does not
// work: on a loaded machine the writer of a result is preempted inside write() by the reader it woke, and a stop
// sent then takes effect as the syscall returns, between two probes, every time. The try returns the probe's
// total wall time and the stop's length as the parent's clock saw it; 0, 0 when the stop did not fall inside the
// probe's call (a parent starved for the rest of the probe), which a retry takes care of.
struct ProbingChild {
  pid_t pid = -1;
  int results = -1;
  ~ProbingChild() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    if (results >= 0) ::close(results);
  }
};

constexpr std::uint64_t kLongProbeSteps = 50'000'000;

double seconds_since_boot() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double cpu_seconds_of(pid_t pid) {
  clockid_t clock;
  if (clock_getcpuclockid(pid, &clock) != 0) return -1;
  timespec t{};
  if (clock_gettime(clock, &t) != 0) return -1;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct StoppedProbe {
  double probe_total_ns = 0;
  double stop_ns = 0;
};

StoppedProbe stop_a_long_probe() {
  int results[2];
  REQUIRE(pipe(results) == 0);
  ProbingChild child;
  child.results = results[0];
  child.pid = fork();
  if (child.pid == 0) {
    close(results[0]);
    // The probe's result, and when the call began and ended (CLOCK_MONOTONIC: the parent's clock too).
    double sent[3];
    sent[1] = seconds_since_boot();
    sent[0] = nz::probe_ns_per_million_steps(kLongProbeSteps);
    sent[2] = seconds_since_boot();
    const ssize_t written = write(results[1], sent, sizeof sent);
    _exit(written == static_cast<ssize_t>(sizeof sent) ? 0 : 1);
  }
  close(results[1]);
  REQUIRE(child.pid > 0);
  // Inside the probe: 10 ms of the child's CPU spent (polled; bounded by 20 s of the parent's clock).
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (cpu_seconds_of(child.pid) < 0.010 && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  REQUIRE(cpu_seconds_of(child.pid) >= 0.010);
  REQUIRE(kill(child.pid, SIGSTOP) == 0);
  int status = 0;
  const pid_t changed = waitpid(child.pid, &status, WUNTRACED);
  REQUIRE(changed == child.pid);
  if (!WIFSTOPPED(status)) return {};  // it had already finished and exited
  const double stopped = seconds_since_boot();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const double resumed = seconds_since_boot();
  REQUIRE(kill(child.pid, SIGCONT) == 0);
  double got[3];
  REQUIRE(read(results[0], got, sizeof got) == static_cast<ssize_t>(sizeof got));
  // A parent starved between its CPU check and the stop may stop the child after its probe: a retry.
  if (!(got[1] <= stopped && resumed <= got[2])) return {};
  return {got[0] * static_cast<double>(kLongProbeSteps) / 1e6, 1e9 * (resumed - stopped)};  // the guard reaps
}

TEST_CASE("the probe counts lost CPU: a probe stopped for 300 ms reports at least that", "[cpu_probe]") {
  // The stop is confirmed by the kernel (waitpid reports the child stopped) and timed by this process's clock,
  // so the probe must report at least that long. A probe that read a CPU-time clock would report ~100 ms.
  // Up to 5 tries, only for a stop that did not fall inside the probe; each takes ~0.5 s on an idle core.
  StoppedProbe seen;
  for (int attempt = 0; attempt < 5 && seen.stop_ns == 0; ++attempt) seen = stop_a_long_probe();
  INFO("probe " << seen.probe_total_ns / 1e6 << " ms in all, stopped for " << seen.stop_ns / 1e6 << " ms");
  REQUIRE(seen.stop_ns >= 300e6);
  CHECK(seen.probe_total_ns >= seen.stop_ns);
}
