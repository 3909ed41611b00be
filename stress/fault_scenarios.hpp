// fault_scenarios.hpp — frontsteal-stress's fault injection: the stealing scheduler (Fenced, chaos backend) with a
// worker that stalls holding most of the work, an item function that throws, and the edge sizes (P = 1, P > N,
// N = 0). Each must keep every item exactly once; a frame that stops moving ends the run (stress/watchdog.hpp).
#pragma once

#include <string>
#include <vector>

#include "stress/stress_options.hpp"

namespace frontsteal::stress {

struct FaultResult {
  std::string name;
  bool passed = false;
  std::string detail;
};

// Every fault scenario, in order, each line printed on stdout as it ends.
std::vector<FaultResult> run_faults(const Options& o);

}  // namespace frontsteal::stress
