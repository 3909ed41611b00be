// plots.hpp — the main job's plots: speed-up against P (one line per scheduler, the ideal dashed), and
// frame time along the path at the largest P not above the core count, as gnuplot data and a script in the
// results directory; gnuplot runs unless --no-plot.
#pragma once

#include "reporting/results_dir.hpp"
#include "schedulers/main_job/analysis.hpp"

namespace frontsteal::main_job {

void write_plots(const Measured& m, const Analysis& a, const report::ResultsDir& dir);

}  // namespace frontsteal::main_job
