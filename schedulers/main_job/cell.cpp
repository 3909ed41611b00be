// cell.cpp — the per-frame accounting and audits of a main-job cell (cell.hpp).
#include "schedulers/main_job/cell.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "measure/cpu_speed_probe.hpp"

namespace frontsteal::main_job {

double account_frame(Cell& c, int f, const FrameOutcome& frame, std::uint64_t serial_triangles) {
  const FrameStats& st = frame.stats;
  c.totals += st.totals();
  if (c.per_worker.size() < st.workers.size()) c.per_worker.resize(st.workers.size());
  for (std::size_t w = 0; w < st.workers.size(); ++w) c.per_worker[w] += st.workers[w];
  c.busy_over_available += static_cast<double>(st.totals().busy_ns);
  c.available += static_cast<double>(st.wall_ns) * st.workers.size();
  c.imbalance_sum += st.imbalance();
  c.imbalance_max = std::max(c.imbalance_max, st.imbalance());
  ++c.frames_run;
  // The audits, in this order: exactly once, the tessellation's own audit, the triangle count.
  const std::string at = "frame " + std::to_string(f) + ": ";
  if (!frame.audit.exactly_once()) {
    ++c.audit_failures;
    if (c.first_problem.empty()) {
      std::ostringstream s;
      s << at << frame.audit;
      c.first_problem = s.str();
    }
  }
  if (frame.inconsistent > 0) {
    c.tessellation_inconsistencies += frame.inconsistent;
    if (c.first_problem.empty()) {
      c.first_problem = at + std::to_string(frame.inconsistent) + " surfaces fail the tessellation audit" +
                        (frame.first_inconsistent.empty() ? "" : " (first: " + frame.first_inconsistent + ")");
    }
  }
  if (frame.triangles != serial_triangles) {
    ++c.triangle_mismatches;
    if (c.first_problem.empty()) {
      c.first_problem =
          at + std::to_string(frame.triangles) + " triangles, serial loop made " + std::to_string(serial_triangles);
    }
  }
  return static_cast<double>(st.wall_ns) / 1e6;
}

TimedFrame time_frame(sc::Scheduler& scheduler, sc::ItemFunctionRef item, std::uint64_t planted_steps) {
  using Clock = std::chrono::steady_clock;
  TimedFrame t;
  const Clock::time_point start = Clock::now();
  t.stats = &scheduler.run_frame(item);
  const Clock::time_point returned = Clock::now();
  if (planted_steps > 0) nz::probe_ns_per_million_steps(planted_steps);
  t.frame_ns = std::chrono::duration<double, std::nano>(returned - start).count();
  t.planted_ns = std::chrono::duration<double, std::nano>(Clock::now() - returned).count();
  return t;
}

}  // namespace frontsteal::main_job
