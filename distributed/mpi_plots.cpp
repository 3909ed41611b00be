// mpi_plots.cpp — frontsteal-mpi's plots (mpi_plots.hpp).
#include "distributed/mpi_plots.hpp"

#include <algorithm>
#include <sstream>

#include "distributed/mpi_options.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::mpi {

void write_run_plots(const std::string& dir_name, const std::string& title,
                     const std::vector<SchedulerResult>& results) {
  const report::ResultsDir dir(std::string(kProgram), dir_name);
  std::ostringstream frames;  // one gnuplot index per scheduler: frame, ms
  for (const SchedulerResult& r : results) {
    frames << "\"" << r.name << "\"\n";
    for (std::size_t f = 0; f < r.frame_s.size(); ++f) frames << f << ' ' << 1000 * r.frame_s[f] << '\n';
    frames << "\n\n";
  }
  dir.write("frontsteal-mpi-frames.dat", frames.str());
  // One row per scheduler and rank: label, busy s, idle s, and the rest of the frames' wall time (rank 0's
  // clock): the owner's protocol cost and progress calls, preemption, the frame barrier.
  std::ostringstream ranks;
  ranks << "# scheduler/rank busy_s idle_s other_s\n";
  for (const SchedulerResult& r : results) {
    double wall = 0;
    for (double f : r.frame_s) wall += f;
    for (std::size_t k = 0; k < r.ranks.size(); ++k) {
      const RankStats& st = r.ranks[k];
      ranks << '"' << r.name << " r" << k << "\" " << st.busy_s << ' ' << st.idle_s << ' '
            << std::max(0.0, wall - st.busy_s - st.idle_s) << '\n';
    }
  }
  dir.write("frontsteal-mpi-ranks.dat", ranks.str());
  std::ostringstream gp;
  gp << "set grid\nset key outside bottom center horizontal\n"
     << "set output 'frontsteal-mpi-frames.png'\n"
     << "set title \"Frame time per scheduler (measured)\\n"
     << report::gnuplot_text(title, true) << "\"\n"
     << "set xlabel 'frame'\nset ylabel 'ms'\nset yrange [0:*]\n"
     << "plot for [i=0:" << (results.empty() ? 0 : results.size() - 1)
     << "] 'frontsteal-mpi-frames.dat' index i using 1:2 with linespoints lt 1+i pt 1+i title columnheader(1)\n"
     << "set output 'frontsteal-mpi-ranks.png'\n"
     << "set title \"Busy and idle time per rank, all frames (measured)\\n"
     << report::gnuplot_text(title, true) << "\"\n"
     << "set style data histograms\nset style histogram rowstacked\nset style fill solid 0.8 border -1\n"
     << "set boxwidth 0.75\nset xtics rotate by -45\nset ylabel 's'\nset xlabel ''\nunset xrange\n"
     << "plot 'frontsteal-mpi-ranks.dat' using 2:xtic(1) title 'busy (items)' lc rgb '#3b75af', "
        "'' using 3 title 'idle (stealing, waiting)' lc rgb '#f0a030', "
        "'' using 4 title 'rest of the frame (protocol, progress calls, preemption, barrier)' lc rgb '#c8c8c8'\n";
  dir.write_gnuplot("frontsteal-mpi.gp", {1100, 640, "font 'sans,10' noenhanced"}, gp.str());
  dir.plot("frontsteal-mpi.gp");
}

}  // namespace frontsteal::mpi
