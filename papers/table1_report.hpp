// table1_report.hpp — the paper's Table 1 beside ours: static load distribution, round robin against a
// spatial partition (the paper's graph partition by simulated annealing; ours schedulers/static_assignment.hpp).
//
// Per stand-in scene: MEASURED at P = cores (the real schedulers, interleaved repeats, paired verdict of
// spatial against round robin with the noise monitor's judgement), SIMULATED at P = cores (to validate the
// simulator against the measured rows) and at the paper's P = 25. Writes table1.{md,csv,json,dat,gp} and
// table1.png into --out and prints the markdown.
#pragma once

#include "papers/paper_run.hpp"

namespace frontsteal::papers {

// Exit status: 0; throws on an audit failure or a file that cannot be written.
int run_table1(PaperRun& run);

}  // namespace frontsteal::papers
