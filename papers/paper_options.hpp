// paper_options.hpp — frontsteal-paper's command line: one subcommand per artifact, and the options they share.
//
// Every option is the parent's, so it is accepted before or after the subcommand (`table1 --frames 2` and
// `--frames 2 table1` mean the same); the subcommands themselves (their names and one-line summaries) come from
// the caller's registration table (paper_main.cpp), so adding one does not touch this file. Parsing goes
// through reporting/command_line.hpp (CLI11): defaults in --help, a mistake exits 2 naming the flag.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::papers {

struct Options {
  std::string command;  // the subcommand given
  std::string out = "results/papers";
  std::vector<std::string> scenes;   // empty: the command's stand-ins
  std::string scene = "plant:5302";  // trace
  std::string trace, calibration;
  std::string validation;  // fig8: validation.json whose held-out error draws the simulated curves' band
  int frames = 24, repeats = 3, passes = 3;
  WorkerId max_p = 64;
  int updates = 150;
  double rate = 30;
  bool null_renderer = false;
  int cost_multiplier = 0;  // table2's bound row: 0 auto, -1 off, else K
  std::uint64_t seed = 1;
  bool plot = true, quiet = false;
};

struct SubcommandSummary {
  std::string name;
  std::string summary;  // one paragraph for --help
};

// Parses argv. --help: the options on stdout, exit 0; a mistake (or no subcommand): exit 2 naming the flag.
Options parse_options(int argc, char** argv, const std::vector<SubcommandSummary>& subcommands);

}  // namespace frontsteal::papers
