// validation_report.hpp — what `frontsteal-paper validate` writes (validate_command.hpp measures, this file
// tabulates): every cell's predicted and measured path time, the error summaries (calibration set, held-out
// sets, per P, per scheduler) against the goal, stealing's lead over the queue measured and predicted, and the
// constants used — validation.md, validation.json, validation.csv and validation-calibration.txt.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "papers/calibration.hpp"
#include "papers/validation.hpp"

namespace frontsteal::papers {

// One measured cell and its two predictions (the current model and the old one, without the new terms).
struct ValidationRow {
  const MeasuredSet* set;
  MeasuredCell cell;
  bool held_out;
  double predicted_ms, baseline_ms;
  double predicted_vs_serial = 0, predicted_vs_queue = 0;  // predicted ratios (0: not predicted)
};

struct ValidationRun {
  std::string machine;                           // this machine: the traces and, unless from a file, the constants
  std::vector<MeasuredSet> sets;                 // sorted by name
  const MeasuredSet* calibration_set = nullptr;  // one of sets
  Overheads constants;
  std::string constants_file;                   // --calibration, or "" when measured here
  std::optional<AffinityMeasurement> affinity;  // when measured here
  int affinity_repeats = 0;
  double trace_scale = 0;
  int trace_passes = 0;
  std::vector<unsigned> threads;
  std::vector<ValidationRow> rows;
};

// Writes the four files into `out`; prints the summary tables unless quiet, and the files written.
void write_validation_report(const ValidationRun& run, const std::string& out, bool quiet);

}  // namespace frontsteal::papers
