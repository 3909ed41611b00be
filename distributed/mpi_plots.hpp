// mpi_plots.hpp — frontsteal-mpi --plots DIR: what a reader would rather look at than read, as data, a
// gnuplot script and PNGs (reporting/results_dir.hpp: a missing gnuplot is a warning, the script stays).
//   frontsteal-mpi-frames.png  frame time along the frames, one line per scheduler (measured)
//   frontsteal-mpi-ranks.png   each rank's busy, idle and remaining seconds per scheduler: the imbalance
//                              stealing removes, and what the protocol and the transport cost
//   frontsteal-mpi-frames.dat, frontsteal-mpi-ranks.dat, frontsteal-mpi.gp  the data and the script
#pragma once

#include <string>
#include <vector>

#include "distributed/rank_stats.hpp"

namespace frontsteal::mpi {

// `title` heads both plots (ranks, scene, frames, how the owner progressed). Throws std::runtime_error naming
// a file that cannot be written.
void write_run_plots(const std::string& dir, const std::string& title, const std::vector<SchedulerResult>& results);

}  // namespace frontsteal::mpi
