// pass_usage.cpp — getrusage(RUSAGE_THREAD) around a pass (pass_usage.hpp).
#include "measure/pass_usage.hpp"

namespace frontsteal::noise {

namespace {

double ms(const timeval& t) { return 1e3 * static_cast<double>(t.tv_sec) + 1e-3 * static_cast<double>(t.tv_usec); }

}  // namespace

PassMeter::PassMeter() : t0_(std::chrono::steady_clock::now()) { getrusage(RUSAGE_THREAD, &start_); }

PassUsage PassMeter::stop() const {
  rusage now{};
  getrusage(RUSAGE_THREAD, &now);
  PassUsage u;
  u.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  u.user_ms = ms(now.ru_utime) - ms(start_.ru_utime);
  u.system_ms = ms(now.ru_stime) - ms(start_.ru_stime);
  u.faults = (now.ru_minflt - start_.ru_minflt) + (now.ru_majflt - start_.ru_majflt);
  u.voluntary_switches = now.ru_nvcsw - start_.ru_nvcsw;
  u.involuntary_switches = now.ru_nivcsw - start_.ru_nivcsw;
  return u;
}

std::map<std::string, std::vector<double>> pass_usage_columns(const std::vector<PassUsage>& passes) {
  std::map<std::string, std::vector<double>> c;
  for (const char* key : {"wall_ms", "user_ms", "system_ms", "faults", "voluntary_switches", "involuntary_switches"}) {
    c[key];
  }
  for (const PassUsage& p : passes) {
    c["wall_ms"].push_back(p.wall_ms);
    c["user_ms"].push_back(p.user_ms);
    c["system_ms"].push_back(p.system_ms);
    c["faults"].push_back(static_cast<double>(p.faults));
    c["voluntary_switches"].push_back(static_cast<double>(p.voluntary_switches));
    c["involuntary_switches"].push_back(static_cast<double>(p.involuntary_switches));
  }
  return c;
}

bool same_work_on_cpu(const std::vector<PassUsage>& passes) {
  if (passes.empty()) return false;
  for (const PassUsage& p : passes) {
    if (p.faults != 0 || p.voluntary_switches != 0 || p.system_ms > 0.01 * p.wall_ms) return false;
    if (p.user_ms + p.system_ms < 0.98 * p.wall_ms) return false;
  }
  return true;
}

}  // namespace frontsteal::noise
