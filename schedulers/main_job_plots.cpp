// main_job_plots.cpp — frontsteal-speedup.dat, frontsteal-frames.dat and frontsteal.gp (main_job_plots.hpp).
#include "schedulers/main_job_plots.hpp"

#include <algorithm>
#include <sstream>
#include <string>

namespace frontsteal::main_job {

using report::gnuplot_text;

// Plots: speed-up against P (one line per scheduler, the ideal dashed), and frame time along the path at the
// largest P not above the core count. The data and the script are always written; gnuplot runs unless --no-plot.
void write_plots(const Measured& m, const Analysis& a, const report::ResultsDir& dir) {
  const Options& o = m.o;
  std::ostringstream dat;
  for (const auto& name : o.schedulers) {
    dat << "\"" << name << "\"\n";
    for (const Row& r : a.rows) {
      if (r.cell->scheduler == name) dat << r.cell->workers << ' ' << r.speedup << '\n';
    }
    dat << "\n\n";
  }
  dir.write("frontsteal-speedup.dat", dat.str());
  WorkerId best_p = 1;
  for (WorkerId p : o.threads) {
    if (p <= m.cores) best_p = std::max(best_p, p);
  }
  std::ostringstream frames;
  auto block = [&](const std::string& title, const std::vector<std::vector<double>>& per_repeat) {
    frames << "\"" << title << "\"\n";
    const std::vector<double> med = frame_medians(per_repeat, o.frames);
    for (int f = 0; f < o.frames; ++f) frames << f << ' ' << med[f] << '\n';
    frames << "\n\n";
  };
  block("serial loop", m.serial_frame_ms);
  int blocks = 1;
  for (const Row& r : a.rows) {
    if (r.cell->workers != best_p) continue;
    block(r.cell->scheduler + " P=" + std::to_string(best_p), r.cell->frame_ms);
    ++blocks;
  }
  dir.write("frontsteal-frames.dat", frames.str());
  const WorkerId max_p = *std::max_element(o.threads.begin(), o.threads.end());
  std::ostringstream gp;
  gp << "# gnuplot script written by frontsteal; run from " << o.out << ": gnuplot frontsteal.gp\n"
     << "set terminal pngcairo size 1200,760 font 'sans,10'\nset key outside right top\nset grid\n"
     << "set output 'frontsteal-speedup.png'\n"
     << "set title \"Tessellation speed-up over the serial loop (measured): " << gnuplot_text(o.scene) << ", "
     << m.wl.model.surfaces.size() << " surfaces\\n" << gnuplot_text(a.machine) << "\"\n"
     << "set xlabel 'workers P'\nset ylabel 'speed-up (T1 / T_P)'\nset xrange [0.5:" << max_p + 0.5 << "]\n"
     << "set yrange [0:*]\n"
     << "plot for [i=0:" << o.schedulers.size() - 1 << "] 'frontsteal-speedup.dat' index i using 1:2 with "
        "linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1), (x <= " << m.cores << " ? x : " << m.cores
     << ") with lines dashtype 2 lc 'black' title 'ideal'\n"
     << "set output 'frontsteal-frames.png'\n"
     << "set title 'Frame time along the camera path (measured), P = " << best_p
     << (o.path == ts::CameraPathKind::orbit_then_zoom
             ? " (frames 0-" + std::to_string(o.frames / 2 - 1) + " orbit, then zoom)"
             : std::string(" (path ") + ts::name(o.path) + ")")
     << (o.interference ? ", interference on" : "") << "'\n"
     << "set xlabel 'frame'\nset ylabel 'ms'\nset autoscale x\nset yrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1 << "] 'frontsteal-frames.dat' index i using 1:2 with linespoints "
        "lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)\n";
  dir.write("frontsteal.gp", gp.str());
  if (o.plot) dir.plot("frontsteal.gp");
}

}  // namespace frontsteal::main_job
