// checker_report.hpp — the frame every Relacy checker's main shares (frontsteal-modelcheck, -chaselev,
// -publication): the results directory, the clock, the JSON document with the common header, the closing line,
// the two files, and one way to report a run that could not write them. Free of Relacy (only the suites include it).
//
// Why apart from the mains: the three opened and closed their results in the same words; what lies between
// (the sections) is each checker's own.
#pragma once

#include <chrono>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>

#include "reporting/json.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::model {

// One section of a report: its markdown and its part of the JSON document.
struct ReportSection {
  std::string markdown;
  report::Json json;
};

double seconds_since(std::chrono::steady_clock::time_point t0);

class CheckerReport {
 public:
  // Creates `out` (and out/histories/ when `histories`: where failing executions are replayed), starts the
  // clock and opens the JSON document: schema_version 2, program, kind "model-checked (bounded search)", commit.
  CheckerReport(std::string program, std::string out, bool histories);

  std::string markdown;  // the report so far
  report::Json json;     // the JSON document so far

  const report::ResultsDir& dir() const noexcept { return dir_; }
  std::chrono::steady_clock::time_point started() const noexcept { return started_; }
  double seconds() const { return seconds_since(started_); }

  // Writes <stem>.md and <stem>.json as they stand.
  void write(std::string_view stem) const;
  // The ending of a checker that judges one structure: the verdict line with the run time, all_as_expected and
  // seconds in the JSON, both files written, the markdown on stdout and "wrote ..." on stderr (unless quiet).
  // Returns the exit status: 0 when every verdict was as expected, else 1.
  int close(std::string_view stem, bool all_as_expected, bool quiet);

 private:
  std::string program_;
  std::string out_;  // as given, for the "wrote" line
  report::ResultsDir dir_;
  bool histories_;  // failing executions are replayed into histories/
  std::chrono::steady_clock::time_point started_;
};

// Runs a checker's body and returns its exit status. An exception (a results file that cannot be written ...)
// ends the run with "program: reason" on stderr and exit status 1, never with a half-written report unnoticed.
template <class Body>
int run_checker(std::string_view program, Body&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace frontsteal::model
