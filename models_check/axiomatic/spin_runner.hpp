// spin_runner.hpp — runs SPIN on a generated Promela model (promela_export.hpp) and reports whether the final
// state asked about is reachable: the model asserts that it is not, so "reachable" is an assertion violation.
// Needs `spin` and `gcc` on the PATH (bootstrap.sh installs spin); throws std::runtime_error naming the step
// and the directory when one fails, so a missing tool is never read as a verdict.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models_check/axiomatic/promela_export.hpp"

namespace frontsteal::axiomatic {

struct SpinVerdict {
  bool reachable = false;
  std::string states;  // pan's "states, stored" line, for the report
};

inline SpinVerdict run_spin(const LitmusTest& armv8_program, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  {
    std::ofstream pml(dir / "model.pml");
    pml << to_promela(armv8_program);
    if (!pml) throw std::runtime_error("cannot write " + (dir / "model.pml").string());
  }
  const std::string cd = "cd '" + dir.string() + "' && ";
  if (std::system((cd + "spin -a model.pml > spin.txt 2>&1").c_str()) != 0) {
    throw std::runtime_error("spin -a failed in " + dir.string() + " (see spin.txt; is spin installed?)");
  }
  if (std::system((cd + "gcc -O2 -w -DSAFETY -o pan pan.c > gcc.txt 2>&1").c_str()) != 0) {
    throw std::runtime_error("compiling pan failed in " + dir.string() + " (see gcc.txt)");
  }
  std::system((cd + "./pan -m1000000 > pan.txt 2>&1").c_str());  // exits non-zero on a violation
  std::ifstream in(dir / "pan.txt");
  std::stringstream text;
  text << in.rdbuf();
  const std::string out = text.str();
  const auto errors_at = out.find("errors: ");
  if (errors_at == std::string::npos) throw std::runtime_error("pan printed no verdict in " + dir.string());
  if (out.find("max search depth too small") != std::string::npos) {
    throw std::runtime_error("pan's search was truncated in " + dir.string());
  }
  SpinVerdict v;
  v.reachable = std::stoi(out.substr(errors_at + 8)) > 0;
  if (v.reachable && out.find("assertion violated") == std::string::npos) {
    throw std::runtime_error("pan found an error that is not the final-state assertion in " + dir.string());
  }
  if (const auto at = out.find("states, stored"); at != std::string::npos) {
    const auto begin = out.rfind('\n', at);
    v.states = out.substr(begin + 1, at - begin - 1);
    while (!v.states.empty() && v.states.front() == ' ') v.states.erase(0, 1);
  }
  return v;
}

}  // namespace frontsteal::axiomatic
