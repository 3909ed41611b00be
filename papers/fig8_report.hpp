// fig8_report.hpp — Fig. 8's files: NAME.md (per scene the curves at the P the paper's text names, the measured
// comparisons with their intervals, verdicts, CPU time and the noise line; the simulator against measurement;
// the costs the models charge), NAME.csv (long form), NAME.json, NAME-<s>.dat, NAME.gp and NAME.png.
//
// NAME is "fig8", or "simulate-<scene>" for `simulate` (then no measured rows).
#pragma once

#include <string>
#include <vector>

#include "papers/fig8_curves.hpp"
#include "papers/paper_run.hpp"

namespace frontsteal::papers {

// Writes the files into --out, prints the markdown, and warns on stderr when a measured verdict is unreliable.
void write_fig8(const std::vector<SceneCurves>& all, PaperRun& run, const std::string& name);

}  // namespace frontsteal::papers
