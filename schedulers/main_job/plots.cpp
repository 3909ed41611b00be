// plots.cpp — frontsteal-speedup.dat, frontsteal-frames.dat and frontsteal.gp (plots.hpp).
#include "schedulers/main_job/plots.hpp"

#include <algorithm>
#include <sstream>
#include <string>

#include "reporting/table.hpp"
#include "schedulers/main_job/loss_account.hpp"

namespace frontsteal::main_job {

using report::gnuplot_text;

namespace {

bool decided(const ShownComparison& c) {
  return c.reliable && (c.c.decision == measure::Decision::kFaster || c.c.decision == measure::Decision::kSlower ||
                        c.c.decision == measure::Decision::kEquivalent);
}

}  // namespace

// Plots: the paired speed-up over the serial loop against P (exp of the estimate of the per-round log T1 / T_P with
// its 95 % interval; filled marks decided, open marks not decided), every scheduler against queue-mutex (interval
// and margin band, coloured by verdict), and frame time along the path at the largest P not above the core
// count. The data and the script are always written; gnuplot runs unless --no-plot.
void write_plots(const Measured& m, const Analysis& a, const report::ResultsDir& dir) {
  const Options& o = m.o;
  std::ostringstream dat;
  for (const auto& name : o.schedulers) {
    dat << "\"" << name << "\"\n";
    for (const Row& r : a.rows) {
      if (r.cell->scheduler != name || !r.vs_serial.c.chosen().valid) continue;
      const measure::LogInterval& li = r.vs_serial.c.chosen();
      const double sp = 1.0 / li.ratio();
      dat << r.cell->workers << ' ' << sp << ' ' << 1.0 / li.ratio_high() << ' ' << 1.0 / li.ratio_low() << ' '
          << (decided(r.vs_serial) ? std::to_string(sp) : "NaN") << ' '
          << (decided(r.vs_serial) ? "NaN" : std::to_string(sp)) << '\n';
    }
    dat << "\n\n";
  }
  dir.write("frontsteal-speedup.dat", dat.str());
  // The forest of comparisons with queue-mutex: one line per scheduler and P, grouped by verdict for colour.
  const char* groups[] = {"faster", "slower", "equivalent", "not decided"};
  std::ostringstream forest;
  int line = 0;
  std::ostringstream tics;
  for (int g = 0; g < 4; ++g) {
    forest << "\"" << groups[g] << "\"\n";
    int y = 0;
    for (const Row& r : a.rows) {
      if (!r.vs_queue || !r.vs_queue->c.chosen().valid) continue;
      ++y;
      const measure::Decision d = r.vs_queue->c.decision;
      const int group = !r.vs_queue->reliable                 ? 3
                        : d == measure::Decision::kFaster     ? 0
                        : d == measure::Decision::kSlower     ? 1
                        : d == measure::Decision::kEquivalent ? 2
                                                              : 3;
      if (g == 0) {
        tics << (line++ ? ", " : "") << "\"P=" << r.cell->workers << " " << gnuplot_text(r.cell->scheduler) << "\" "
             << -y;
      }
      if (group != g) continue;
      const measure::LogInterval& li = r.vs_queue->c.chosen();
      forest << li.ratio() << ' ' << -y << ' ' << li.ratio_low() << ' ' << li.ratio_high() << '\n';
    }
    forest << "NaN NaN NaN NaN\n";  // keeps every block non-empty for gnuplot
    forest << "\n\n";
  }
  dir.write("frontsteal-verdicts.dat", forest.str());
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
  // Where the time went beyond the items' work: per P and scheduler the account's loss terms stacked (shares of
  // P x T; a term below 0, as unaccounted can be, is drawn as 0), and 1 - limit-efficiency with its interval.
  std::ostringstream account;
  account << "label";
  for (std::size_t i = 1; i < kTerms; ++i) {  // gnuplot's enhanced text would set "off_cpu" as a subscript
    std::string column = name(static_cast<Term>(i));
    std::replace(column.begin(), column.end(), '_', '-');
    account << ' ' << column;
  }
  account << " limit_loss limit_loss_low limit_loss_high\n";
  for (const Row& r : a.rows) {
    account << "\"P=" << r.cell->workers << " " << gnuplot_text(r.cell->scheduler) << "\"";
    for (std::size_t i = 1; i < kTerms; ++i) {
      account << ' ' << std::max(0.0, 100 * r.account.terms.share(static_cast<Term>(i)));
    }
    if (r.vs_limit && r.vs_limit->c.chosen().valid) {
      account << ' ' << 100 * (1 - r.limit_efficiency()) << ' ' << 100 * (1 - r.limit_efficiency_high()) << ' '
              << 100 * (1 - r.limit_efficiency_low()) << '\n';
    } else {
      account << " NaN NaN NaN\n";
    }
  }
  dir.write("frontsteal-account.dat", account.str());
  const WorkerId max_p = *std::max_element(o.threads.begin(), o.threads.end());
  const std::size_t rounds = a.rows.empty() ? 0 : a.rows.front().vs_serial.c.rounds;
  std::ostringstream gp;
  gp << "set key outside right top\nset grid\n"
     << "set output 'frontsteal-speedup.png'\n"
     << "set title \"Paired speed-up over the serial loop (measured; per-round T1 / T(P), 95 % interval; open "
        "marks: not decided): "
     << gnuplot_text(o.scene) << ", " << m.wl.model.surfaces.size() << " surfaces\\n"
     << gnuplot_text(a.machine) << "; " << rounds << " rounds per comparison\"\n"
     << "set xlabel 'workers P'\nset ylabel 'speed-up (T1 / T_P)'\nset xrange [0.5:" << max_p + 0.5 << "]\n"
     << "set yrange [0:*]\n"
     << "plot for [i=0:" << o.schedulers.size() - 1
     << "] 'frontsteal-speedup.dat' index i using 1:2 with "
        "lines lt 1+i%8 dt 1+i/8 title columnheader(1), \\\n  for [i=0:"
     << o.schedulers.size() - 1
     << "] 'frontsteal-speedup.dat' index i using 1:2:3:4 with yerrorbars lt 1+i%8 pt 0 notitle, \\\n  for [i=0:"
     << o.schedulers.size() - 1
     << "] 'frontsteal-speedup.dat' index i using 1:5 with points lt 1+i%8 pt 7 notitle, \\\n"
     << "  for [i=0:" << o.schedulers.size() - 1
     << "] 'frontsteal-speedup.dat' index i using 1:6 with points lt 1+i%8 pt 6 ps 1.5 notitle, \\\n  (x <= " << m.cores
     << " ? x : " << m.cores << ") with lines dashtype 2 lc 'black' title 'ideal'\n"
     << "set output 'frontsteal-verdicts.png'\n"
     << "set title \"Every scheduler against queue-mutex at the same P (measured): per-round time ratio to "
        "queue-mutex, 95 % interval; shaded: the +-"
     << report::fixed_text(100 * o.margin, 1) << " % margin\\n"
     << gnuplot_text(a.machine) << "; " << rounds << " rounds per comparison\"\n"
     << "set xlabel 'time relative to queue-mutex (< 1: faster)'\nunset ylabel\nset ytics (" << tics.str()
     << ") font 'sans,8'\nset autoscale x\nset yrange [" << -(line + 1) << ":0]\nset key outside right top\n"
     << "set object 1 rectangle from " << 1.0 / (1.0 + o.margin) << ", graph 0 to " << 1.0 + o.margin
     << ", graph 1 fillcolor rgb '#dddddd' fillstyle solid 0.5 noborder behind\n"
     << "plot for [i=0:3] 'frontsteal-verdicts.dat' index i using 1:2:3:4 with xerrorbars pt 7 lc i+1 "
        "title columnheader(1), 1/0 notitle\n"
     << "unset object 1\nset ytics autofreq font 'sans,10'\nset key outside right top\n"
     << "set output 'frontsteal-frames.png'\n"
     << "set title 'Frame time along the camera path (measured), P = " << best_p
     << (o.path == ts::CameraPathKind::orbit_then_zoom
             ? " (frames 0-" + std::to_string(o.frames / 2 - 1) + " orbit, then zoom)"
             : std::string(" (path ") + ts::name(o.path) + ")")
     << (o.interference ? ", interference on" : "") << "'\n"
     << "set xlabel 'frame'\nset ylabel 'ms'\nset autoscale x\nset yrange [0:*]\n"
     << "plot for [i=0:" << blocks - 1
     << "] 'frontsteal-frames.dat' index i using 1:2 with linespoints "
        "lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)\n";
  // One fixed colour per term, in the order of the columns (claim ... unaccounted), none repeated.
  static_assert(kTerms == 10, "one colour per loss term below");
  gp << "set output 'frontsteal-account.png'\n"
     << "term_colours = '#1f77b4 #ff7f0e #2ca02c #d62728 #9467bd #8c564b #e377c2 #7f7f7f #bcbd22'\n"
     << "set title \"Where the time went beyond the items' work (measured): the loss account's terms, % of P x T\\n"
        "black: 1 - limit-efficiency with its 95 % interval (the limit: P serial loops at once)\\n"
     << gnuplot_text(a.machine) << "; " << rounds << " rounds per comparison\"\n"
     << "set style data histograms\nset style histogram rowstacked\nset style fill solid 0.85 border -1\n"
     << "set boxwidth 0.75\nset key outside right top\nunset xlabel\nset ylabel '% of P x T'\n"
     << "set xtics rotate by -60 font 'sans,8' nomirror\nset autoscale x\nset yrange [*:*]\n"
     << "plot for [i=2:" << kTerms
     << "] 'frontsteal-account.dat' using i:xtic(1) lc rgb word(term_colours, i-1) title columnheader(i), \\\n"
     // The header line is row 0 of a plain `using`; the histogram's first box stands at x = 0.
     << "  '' using ($0-1):" << kTerms + 1 << ":" << kTerms + 2 << ":" << kTerms + 3
     << " with yerrorbars lc 'black' pt 7 ps 0.8 title '1 - limit-efficiency'\n";
  dir.write_gnuplot("frontsteal.gp", {1200, 760}, gp.str());
  if (o.plot) dir.plot("frontsteal.gp");
}

}  // namespace frontsteal::main_job
