// mpi_report.hpp — frontsteal-mpi's results on rank 0: the per-scheduler table (unchanged columns since issue
// 18's first cut), the medians with 95 % bootstrap intervals and the noise verdict (report::Table: terminal
// and --markdown), and the --json document (docs/results-schema.md, "frontsteal-mpi run").
#pragma once

#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/owner_progress.hpp"
#include "distributed/rank_stats.hpp"
#include "reporting/json.hpp"
#include "reporting/table.hpp"

namespace frontsteal::mpi {

struct RunSummary {
  int ranks = 0;
  std::string scene;
  unsigned items = 0;
  int frames = 0;
  ProgressChoice progress;
  std::uint32_t work_ns = 0;  // synthetic shapes: ns per cost unit (--work-ns)
  std::uint32_t skew = 0;     // synthetic:N's heavy fifth (--skew)
};

// Prints both tables and the noise line to stdout; writes --json and --markdown when asked.
void report_results(const Options& o, const RunSummary& run, const std::vector<SchedulerResult>& results);

// The medians with their intervals: one row per scheduler and rank (frame-time columns on each scheduler's
// first row only).
report::Table intervals_table(const std::vector<SchedulerResult>& results);
// One line: the noise monitor's verdict over every scheduler ("" when every window was quiet).
std::string noise_warning(const std::vector<SchedulerResult>& results);
report::Json run_json(const RunSummary& run, const std::vector<SchedulerResult>& results);

}  // namespace frontsteal::mpi
