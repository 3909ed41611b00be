// checker_options.hpp — the options of the Relacy checkers that judge one structure (frontsteal-modelcheck-chaselev,
// frontsteal-modelcheck-publication): the search budgets, the kill-matrix switch and where results go, spelled
// alike in both. Each checker sets its own defaults first (--help shows them) and adds its own options in between.
#pragma once

#include <cstdint>
#include <string>

#include "reporting/command_line.hpp"

namespace frontsteal::model {

struct SearchBudget {
  std::uint64_t iterations = 100000;        // random search, per policy and scenario
  std::uint64_t mutant_iterations = 20000;  // random search, per mutant and scenario
  unsigned bound = 0;                       // context-bound search; 0: none
  std::uint64_t cap = 0;                    // executions after which a tree search stops (incomplete)
  bool full = false;                        // also the full search
  bool mutants = true;                      // run the kill matrix
  std::string out;
  bool quiet = false;
};

// In --help order: --iterations, --mutant-iterations, --bound (constructor); the checker's own options and
// --cap, --full where it places them; --no-mutants, --out, --quiet (parse).
class CheckerCommandLine {
 public:
  CheckerCommandLine(std::string program, std::string description, std::string footer, SearchBudget& budget,
                     const std::string& bound_help);

  report::CommandLine& cli() noexcept { return cli_; }
  void cap(const std::string& help);
  void full(const std::string& help);
  // Adds --no-mutants, --out and --quiet, then parses: --help exits 0, a mistake exits 2 naming the flag.
  void parse(int argc, char** argv);

 private:
  report::CommandLine cli_;
  SearchBudget& budget_;
};

}  // namespace frontsteal::model
