// checker_options.cpp — CheckerCommandLine: the options chaselev's and publication's checkers share.
#include "models_check/checker_options.hpp"

#include <utility>

namespace frontsteal::model {

namespace {

// Iterations and execution caps: at least one, at most a billion.
CLI::Range count() { return CLI::Range(std::uint64_t{1}, std::uint64_t{1'000'000'000}); }

}  // namespace

CheckerCommandLine::CheckerCommandLine(std::string program, std::string description, std::string footer,
                                       SearchBudget& budget, const std::string& bound_help)
    : cli_(std::move(program), std::move(description), std::move(footer)), budget_(budget) {
  cli_.option("--iterations", budget_.iterations, "random-search iterations per policy and scenario")->check(count());
  cli_.option("--mutant-iterations", budget_.mutant_iterations, "random-search iterations per mutant and scenario")
      ->check(count());
  cli_.option("--bound", budget_.bound, bound_help)->check(CLI::Range(0u, 4u));
}

void CheckerCommandLine::cap(const std::string& help) { cli_.option("--cap", budget_.cap, help)->check(count()); }

void CheckerCommandLine::full(const std::string& help) { cli_.flag("--full", budget_.full, help); }

void CheckerCommandLine::parse(int argc, char** argv) {
  bool no_mutants = false;
  cli_.flag("--no-mutants", no_mutants, "skip the kill matrix");
  cli_.out(budget_.out);
  cli_.quiet(budget_.quiet);
  cli_.parse(argc, argv);
  budget_.mutants = !no_mutants;
}

}  // namespace frontsteal::model
