// mpi_report.hpp — frontsteal-mpi's results on rank 0: the per-scheduler table (unchanged columns since issue
// 18's first cut), the medians with 95 % bootstrap intervals and the noise verdict (report::Table: terminal
// and --markdown), and the --json document (docs/results-schema.md, "frontsteal-mpi run").
#pragma once

#include <string>
#include <vector>

#include "distributed/mpi_options.hpp"
#include "distributed/owner_progress.hpp"
#include "distributed/paired_rounds.hpp"
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
  int threads = 1;            // hier's workers per rank (--threads)
  double chunk_us = 0;        // hier's refill size (--chunk-us)
  bool lifelines = false;     // hier's --lifelines
  bool batch_claims = false;  // hier's --batch-claims
  bool thief_views = true;    // --thief-reads view
};

// The paired comparisons of a --rounds run (paired_rounds.hpp), as reported.
struct PairedReport {
  std::string reference;
  int rounds = 0, frames_per_pass = 0;
  double margin_pct = 0;
  std::vector<ArmComparison> comparisons;
  MethodCheck method;
};

// Prints both tables and the noise line to stdout; writes --json and --markdown when asked. With `paired`, the
// answer in plain words and the paired table come first (stdout, markdown, and "paired" in the JSON).
void report_results(const Options& o, const RunSummary& run, const std::vector<SchedulerResult>& results,
                    const PairedReport* paired = nullptr);

// One row per arm against the reference: time ratio and speed-up with 95 % intervals, the verdict.
report::Table paired_table(const PairedReport& paired);
// The answer first: one line per scheduler ("rma: 1.51x the speed of static-space [1.47, 1.55], faster"), then
// what the A/A twin and the planted arm say about the method in this run.
std::string paired_answer(const PairedReport& paired);

// The medians with their intervals: one row per scheduler and rank (frame-time columns on each scheduler's
// first row only).
report::Table intervals_table(const std::vector<SchedulerResult>& results);
// One line: the noise monitor's verdict over every scheduler ("" when every window was quiet).
std::string noise_warning(const std::vector<SchedulerResult>& results);
report::Json run_json(const RunSummary& run, const std::vector<SchedulerResult>& results);

}  // namespace frontsteal::mpi
