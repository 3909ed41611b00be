// noise_monitor.cpp — parsing /proc and deciding "busy" (noise_monitor.hpp).
#include "measure/noise_monitor.hpp"

#include "measure/interference.hpp"
#include "measure/proc_file.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace frontsteal::noise {

std::string percent(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * share);
  return buf;
}

ProcSample parse_sample(std::string_view proc_stat, std::string_view self_stat, std::string_view loadavg,
                        double wall_s) {
  ProcSample s;
  s.wall_s = wall_s;
  // /proc/stat: the first line is "cpu  user nice system idle iowait irq softirq steal guest guest_nice".
  // guest and guest_nice are already counted in user and nice, so they are left out of the total.
  {
    std::istringstream in{std::string(proc_stat.substr(0, proc_stat.find('\n')))};
    std::string label;
    std::uint64_t v[8] = {};
    in >> label;
    int got = 0;
    while (got < 8 && in >> v[got]) ++got;
    if (label != "cpu" || got < 7) return s;  // steal appeared in Linux 2.6.11; older lines have 7 columns
    s.busy_ticks = v[0] + v[1] + v[2] + v[5] + v[6];
    s.steal_ticks = got > 7 ? v[7] : 0;
    s.total_ticks = s.busy_ticks + v[3] + v[4] + s.steal_ticks;
  }
  // /proc/self/stat: "pid (comm) state ppid …"; comm may hold spaces and parentheses, so fields are counted
  // from the last ')'. utime and stime are fields 14 and 15 (1-based), i.e. the 12th and 13th after it.
  {
    const auto close = self_stat.rfind(')');
    if (close == std::string_view::npos) return s;
    std::istringstream in{std::string(self_stat.substr(close + 1))};
    std::string field;
    std::uint64_t utime = 0, stime = 0;
    for (int i = 3; i <= 15 && in >> field; ++i) {
      if (i == 14) utime = std::strtoull(field.c_str(), nullptr, 10);
      if (i == 15) stime = std::strtoull(field.c_str(), nullptr, 10);
      if (i == 15) s.ok = true;
    }
    if (!s.ok) return s;
    s.self_ticks = utime + stime;
  }
  {
    std::istringstream in{std::string(loadavg)};
    if (!(in >> s.load1)) s.ok = false;
  }
  return s;
}

ProcSample sample_now(pid_t known) {
  const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  ProcSample s = parse_sample(read_proc_file("/proc/stat"), read_proc_file("/proc/self/stat"),
                              read_proc_file("/proc/loadavg"), now);
  if (known > 0) s.known_ticks = interference::process_ticks(known);
  s.children_ticks = children_ticks(::getpid(), known);
  return s;
}

std::uint64_t children_ticks(pid_t parent, pid_t except) {
  std::uint64_t sum = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    pid_t pid = 0;
    const auto [end, err] = std::from_chars(name.data(), name.data() + name.size(), pid);
    if (err != std::errc() || end != name.data() + name.size() || pid == except) continue;
    const std::string stat = read_proc_file("/proc/" + name + "/stat");
    // "pid (comm) state ppid …": the parent is the second field after the last ')'.
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream in(stat.substr(close + 1));
    std::string state;
    long ppid = 0;
    if (!(in >> state >> ppid) || ppid != parent) continue;
    sum += interference::parse_process_ticks(stat).value_or(0);  // gone meanwhile: 0
  }
  return sum;
}

Usage& Usage::operator+=(const Usage& o) {
  total_ticks += o.total_ticks;
  busy_ticks += o.busy_ticks;
  steal_ticks += o.steal_ticks;
  self_ticks += o.self_ticks;
  known_ticks += o.known_ticks;
  children_ticks += o.children_ticks;
  wall_s += o.wall_s;
  windows += o.windows;
  ok = ok && o.ok;
  return *this;
}

std::uint64_t Usage::other_ticks() const {
  const std::uint64_t ours = self_ticks + known_ticks + children_ticks;
  return busy_ticks > ours ? busy_ticks - ours : 0;
}
double Usage::known_share() const {
  return total_ticks ? static_cast<double>(known_ticks) / static_cast<double>(total_ticks) : 0.0;
}
double Usage::other_share() const {
  return total_ticks ? static_cast<double>(other_ticks()) / static_cast<double>(total_ticks) : 0.0;
}
double Usage::steal_share() const {
  return total_ticks ? static_cast<double>(steal_ticks) / static_cast<double>(total_ticks) : 0.0;
}

Usage usage_between(const ProcSample& a, const ProcSample& b) {
  Usage u;
  u.ok = a.ok && b.ok && b.total_ticks >= a.total_ticks;
  u.windows = 1;
  u.wall_s = b.wall_s - a.wall_s;
  if (!u.ok) return u;
  // Counters only grow; a smaller value would be a wrapped or reset counter: count nothing.
  auto delta = [](std::uint64_t x, std::uint64_t y) { return y >= x ? y - x : 0; };
  u.total_ticks = delta(a.total_ticks, b.total_ticks);
  u.busy_ticks = delta(a.busy_ticks, b.busy_ticks);
  u.steal_ticks = delta(a.steal_ticks, b.steal_ticks);
  u.self_ticks = delta(a.self_ticks, b.self_ticks);
  u.known_ticks = delta(a.known_ticks, b.known_ticks);           // a co-runner reaped in the window counts 0, not less
  u.children_ticks = delta(a.children_ticks, b.children_ticks);  // likewise a child that exited
  return u;
}

Assessment assess(const Usage& u, const Thresholds& t) {
  Assessment a;
  if (!u.ok) {
    // Cannot tell: say so rather than call the machine quiet.
    a.busy = true;
    a.reason = "/proc could not be read";
    return a;
  }
  if (u.other_share() > t.other_share && u.other_ticks() >= kMinOtherTicks) {
    a.busy = true;
    a.reason = "other processes used " + percent(u.other_share()) + " of the machine (threshold " +
               percent(t.other_share) + ")";
  }
  if (u.steal_share() > t.steal_share && u.steal_ticks >= kMinOtherTicks) {
    a.busy = true;
    a.reason += std::string(a.reason.empty() ? "" : "; ") + "the hypervisor stole " + percent(u.steal_share()) +
                " (threshold " + percent(t.steal_share) + ")";
  }
  return a;
}

double spread_of(const std::vector<double>& values) {
  if (values.size() < 2) return 0;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return *lo > 0 ? *hi / *lo - 1.0 : 0.0;
}

}  // namespace frontsteal::noise
