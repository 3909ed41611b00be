// fig8_report.cpp — Fig. 8's markdown, CSV, JSON and gnuplot files (fig8_report.hpp).
#include "papers/fig8_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "papers/measured_noise.hpp"
#include "reporting/table.hpp"

namespace frontsteal::papers {

namespace {

// fig8.json's (and simulate-*.json's) schema (docs/results-schema.md). 2: the common header of reporting/ and
// the noise verdict in the comparisons (schema 1, by hand, had no schema_version, program or kind; its
// "verdict" was never "unreliable"); every key of schema 1 is kept.
constexpr int kSchemaVersion = 2;

// The band around the simulated curves: the validated model's held-out median |error| on speed-up ratios
// (validation.md, "Ratios"), read from --validation (or DIR/validation.json). Ratios, because they are what the
// validation could test on a machine whose speed changes; the band says how far a simulated point may be from
// what this machine would measure, not a confidence interval.
struct ErrorBand {
  double pct = 0;      // 0: no band
  std::string source;  // the file, or why there is no band
};

ErrorBand error_band(const PaperRun& run) {
  const Options& o = run.options();
  ErrorBand band;
  const std::string file =
      !o.validation.empty() ? o.validation : (std::filesystem::path(o.out) / "validation.json").string();
  std::ifstream in(file);
  if (!in) {
    band.source = o.validation.empty() ? "no validation.json beside the results: simulated curves without error band"
                                       : "cannot read " + file + ": simulated curves without error band";
    return band;
  }
  try {
    const report::Json js = report::Json::parse(in);
    for (const auto& r : js.at("ratio_summary")) {
      if (r.at("ratios").get<std::string>().rfind("speed-up ratios", 0) == 0) {
        band.pct = r.at("median_abs_error_pct").get<double>();
        band.source =
            file + " (held-out median |error| of " + std::to_string(r.at("n").get<int>()) + " speed-up ratios)";
      }
    }
  } catch (const std::exception& e) {
    band.source = file + " unreadable (" + e.what() + "): simulated curves without error band";
  }
  return band;
}

// The curves at the P the paper's text names: measured rows, then simulated at 1-4, 8, 16, 32, 64 and the last.
report::Table curve_table(const SceneCurves& c) {
  std::vector<report::Column> cols = {{"workers", "P"}, {"source", "source", false}};
  for (const auto& m : kFig8Models) cols.push_back({m.scheduler, m.label});
  cols.push_back({"queue_vs_static", "queue / static"});
  cols.push_back({"stealing_vs_queue", "stealing / queue"});
  report::Table t(cols);
  auto add = [&](WorkerId p, const char* source, const PerModel<double>& fps) {
    std::vector<report::Cell> row = {p, source};
    for (double v : fps) row.push_back(report::Cell::fixed(v, 2));
    row.push_back(pct_change(fps[kQueueModel] / fps[kStaticModel]));
    row.push_back(pct_change(fps[kStealingModel] / fps[kQueueModel]));
    t.add_row(std::move(row));
  };
  for (std::size_t i = 0; i < c.meas_ps.size(); ++i) add(c.meas_ps[i], "MEASURED", c.meas_fps[i]);
  for (std::size_t i = 0; i < c.sim_ps.size(); ++i) {
    const WorkerId p = c.sim_ps[i];
    if (!(p <= 4 || p == 8 || p == 16 || p == 32 || p == 64 || p == c.sim_ps.back())) continue;
    PerModel<double> fps{};
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) fps[m] = c.sim[i][m].frames_per_s;
    add(p, "SIMULATED", fps);
  }
  return t;
}

report::Table verdict_table(const SceneCurves& c) {
  report::Table t({{"workers", "P"},
                   {"queue_vs_static", "global queue / static", false},
                   {"stealing_vs_queue", "load stealing / global queue", false}});
  for (std::size_t i = 0; i < c.meas_ps.size(); ++i) {
    t.add_row({c.meas_ps[i], c.meas_verdicts[i][0].text(), c.meas_verdicts[i][1].text()});
  }
  return t;
}

std::string markdown(const std::vector<SceneCurves>& all, PaperRun& run, const VerdictTally& tally,
                     const ErrorBand& band) {
  const Options& o = run.options();
  std::ostringstream md;
  md << "# Fig. 8: static vs global queue vs load stealing, tessellation rate against processors\n\n"
     << run.stamp()
     << "\n\nThe paper's models are not available; ours are **procedural stand-ins** with the paper's surface "
        "counts (`plant:N`), tessellated along the main job's camera path ("
     << o.frames
     << " frames: orbit, then "
        "zoom). Tessellation rate = whole-model tessellations (frames) per second. **MEASURED** = the real "
        "schedulers on this machine (median of "
     << o.repeats
     << " interleaved repeats); **SIMULATED** = the "
        "trace-driven models of papers/simulator.hpp replaying the per-surface costs this machine measured, "
        "with costs from calibration.md. Chase-Lev is not in the paper; it is the modern baseline.\n\n"
     << "The paper prints Fig. 8 as a plot; its text gives: the global queue is 5-10% faster than static, load "
        "stealing another 10-20% faster than the queue, and stealing scales close to linearly (Onyx, 4 CPUs; a "
        "Challenge for more).\n\n![Fig. 8](fig8.png)\n\n"
     << (band.pct > 0
             ? "Shaded around each simulated curve: ±" + fixed(band.pct, 1) + " %, the simulator's " + band.source + "."
             : "Simulated curves without an error band: " + band.source + ".")
     << "\n";
  for (const SceneCurves& c : all) {
    md << "\n## `" << c.scene << "` (" << c.surfaces << " surfaces; serial " << fixed(c.serial_fps, 2)
       << " frames/s from the trace)\n\n"
       << curve_table(c).markdown();
    md << "\nMeasured, round by round (path-time ratio [95 % interval] verdict: " << comparison_method(o.repeats)
       << "):\n\n"
       << verdict_table(c).markdown();
    if (!c.meas_ps.empty()) {
      md << "\nWorkers' CPU time over wall × P, measured (below utilization when a worker lost its CPU): ";
      for (std::size_t i = 0; i < c.meas_ps.size(); ++i) {
        md << "P = " << c.meas_ps[i] << ':';
        for (std::size_t m = 0; m < kFig8ModelCount; ++m)
          md << ' ' << kFig8Models[m].scheduler << ' ' << fixed(c.meas_cpu_pct[i][m], 1) << '%';
        md << (i + 1 < c.meas_ps.size() ? "; " : ".\n\n");
      }
      md << c.noise_line << '\n';
    }
    md << "\nSimulated speed-up at P = " << c.sim_ps.back() << " (over the serial trace): ";
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      md << kFig8Models[m].label << ' ' << fixed(c.sim.back()[m].frames_per_s / c.serial_fps, 1) << "x"
         << (m + 1 < kFig8ModelCount ? ", " : "");
    }
    md << "; utilization ";
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      md << fixed(c.sim.back()[m].utilization_pct, 1) << "%" << (m + 1 < kFig8ModelCount ? " / " : ".\n");
    }
  }
  md << "\n## Simulator against measurement (frames/s; error = simulated / measured - 1)\n\n"
     << "Work inflation = the measured Σ busy time (time inside items, all workers) over the same at P = 1: "
        "how much slower the items themselves ran beside each other (shared caches, memory, SMT siblings, a "
        "noisy host). The models replay the serial costs and do not charge it.\n\n";
  report::Table errors({{"scene", "scene", false},
                        {"workers", "P"},
                        {"model", "model", false},
                        {"measured", "measured"},
                        {"simulated", "simulated"},
                        {"error", "error"},
                        {"work_inflation", "work inflation"}});
  double worst = 0, sum_abs = 0;
  int count = 0;
  for (const SceneCurves& c : all) {
    for (std::size_t i = 0; i < c.meas_ps.size(); ++i) {
      for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
        const double err = c.sim_at_meas_fps[i][m] / c.meas_fps[i][m] - 1.0;
        worst = std::max(worst, std::abs(err));
        sum_abs += std::abs(err);
        ++count;
        errors.add_row({"`" + c.scene + "`", c.meas_ps[i], kFig8Models[m].label,
                        report::Cell::fixed(c.meas_fps[i][m], 2), report::Cell::fixed(c.sim_at_meas_fps[i][m], 2),
                        pct_change(1.0 + err), report::Cell::fixed(c.meas_busy_ms[i][m] / c.meas_busy_ms[0][m], 3)});
      }
    }
  }
  md << errors.markdown();
  if (count) {
    md << "\nMean absolute error " << fixed(100.0 * sum_abs / count, 1) << "%, worst " << fixed(100.0 * worst, 1)
       << "% over " << count << " measured points (P = 1 ... " << hardware_cores()
       << " only: no bigger machine was "
          "available to this run).\n";
  }
  if (tally.unreliable) md << '\n' << tally.warning();
  md << "\n## Costs the models charge (measured by microbenchmarks)\n\n" << describe(run.overheads());
  return md.str();
}

// Long form: per scene every simulated P and model, then the measured points.
report::Table csv_table(const std::vector<SceneCurves>& all) {
  report::Table t({{"source", "source", false},
                   {"scene", "scene", false},
                   {"surfaces", "surfaces"},
                   {"workers", "P"},
                   {"model", "model", false},
                   {"scheduler", "scheduler", false},
                   {"frames_per_s", "frames/s"},
                   {"utilization_pct", "utilization (%)"},
                   {"imbalance_mean", "imbalance"},
                   {"steals", "steals"},
                   {"failed_steals", "failed steals"},
                   {"lock_waits", "lock waits"}});
  for (const SceneCurves& c : all) {
    const auto surfaces = static_cast<std::uint64_t>(c.surfaces);
    for (std::size_t i = 0; i < c.sim_ps.size(); ++i) {
      for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
        const SimulatedRun& r = c.sim[i][m];
        t.add_row({"simulated", c.scene, surfaces, c.sim_ps[i], kFig8Models[m].label, kFig8Models[m].scheduler,
                   report::Cell::fixed(r.frames_per_s, 2), report::Cell::fixed(r.utilization_pct, 1),
                   report::Cell::fixed(r.imbalance_mean, 3), r.steals, r.failed_steals, r.lock_waits});
      }
    }
    for (std::size_t i = 0; i < c.meas_ps.size(); ++i) {
      for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
        t.add_row({"measured", c.scene, surfaces, c.meas_ps[i], kFig8Models[m].label, kFig8Models[m].scheduler,
                   report::Cell::fixed(c.meas_fps[i][m], 2), report::Cell::empty(), report::Cell::empty(),
                   report::Cell::empty(), report::Cell::empty(), report::Cell::empty()});
      }
    }
  }
  return t;
}

report::Json scene_json(const SceneCurves& c) {
  report::Json simulated = report::Json::array(), measured = report::Json::array();
  for (std::size_t i = 0; i < c.sim_ps.size(); ++i) {
    report::Json fps = report::Json::array();
    for (const SimulatedRun& r : c.sim[i]) fps.push_back(r.frames_per_s);
    simulated.push_back({{"workers", c.sim_ps[i]}, {"fps", fps}});
  }
  for (std::size_t i = 0; i < c.meas_ps.size(); ++i) {
    measured.push_back({{"workers", c.meas_ps[i]},
                        {"fps", c.meas_fps[i]},
                        {"path_ms_per_repeat", c.meas_path_ms[i]},
                        {"queue_vs_static", c.meas_verdicts[i][0].json()},
                        {"stealing_vs_queue", c.meas_verdicts[i][1].json()},
                        {"cpu_pct", c.meas_cpu_pct[i]}});
  }
  report::Json scene = {{"scene", c.scene},
                        {"surfaces", c.surfaces},
                        {"serial_fps", c.serial_fps},
                        {"simulated", simulated},
                        {"measured", measured}};
  if (!c.noise.is_null()) scene["noise"] = c.noise;
  return scene;
}

// NAME-<s>.dat per scene and NAME.gp: a row of rate plots, a row of efficiency (% of ideal) plots.
void write_plot(const std::vector<SceneCurves>& all, PaperRun& run, const std::string& name, const ErrorBand& band) {
  const double e = band.pct / 100.0;
  std::ostringstream gp, gp_efficiency;
  gp << "set output '" << name << ".png'\n"
     << "set multiplot layout 2," << all.size()
     << " title \"Tessellation rate against processors: lines SIMULATED "
        "(trace-driven)"
     << (e > 0 ? ", shaded +-" + fixed(band.pct, 1) + " % (held-out median error)" : ", no error band")
     << ", points MEASURED\\n"
     << machine_line() << ", commit " << run.commit() << "\"\n"
     << "set grid\nset key left top font ',8'\nset xlabel 'processors P'\n";
  gp_efficiency << "set ylabel '% of ideal (serial trace x P)'\nset yrange [0:110]\nset key left bottom font ',8'\n";
  const char* colours[] = {"#d62728", "#ff7f0e", "#1f77b4", "#2ca02c"};
  for (std::size_t s = 0; s < all.size(); ++s) {
    const SceneCurves& c = all[s];
    const std::string dat = name + "-" + std::to_string(s) + ".dat";
    std::ostringstream d;
    d << "# P, simulated fps per model, then measured fps per model (NaN where not measured)\n";
    for (std::size_t i = 0; i < c.sim_ps.size(); ++i) {
      d << c.sim_ps[i];
      for (const auto& r : c.sim[i]) d << ' ' << r.frames_per_s;
      const auto at = std::find(c.meas_ps.begin(), c.meas_ps.end(), c.sim_ps[i]);
      for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
        d << ' ' << (at != c.meas_ps.end() ? std::to_string(c.meas_fps[at - c.meas_ps.begin()][m]) : "NaN");
      }
      d << '\n';
    }
    run.dir().write(dat, d.str());
    gp << "set title '" << c.scene << " (" << c.surfaces << " surfaces)'\nset ylabel 'frames per second'\n"
       << "plot '" << dat << "' using 1:(" << c.serial_fps
       << "*$1) with lines dt 2 lc 'gray40' title 'ideal (serial x P)'";
    gp_efficiency << "set title '" << c.scene << ": efficiency'\nplot '" << dat
                  << "' using 1:(100) with lines dt 2 "
                     "lc 'gray40' title 'ideal'";
    for (std::size_t m = 0; e > 0 && m < kFig8ModelCount; ++m) {
      const std::string col = "$" + std::to_string(2 + m);
      gp << ", '' using 1:(" << col << "*" << 1 - e << "):(" << col << "*" << 1 + e
         << ") with filledcurves fs transparent solid 0.15 noborder lc rgb '" << colours[m] << "' notitle";
      gp_efficiency << ", '' using 1:(100*" << col << "*" << 1 - e << "/(" << c.serial_fps << "*$1)):(100*" << col
                    << "*" << 1 + e << "/(" << c.serial_fps
                    << "*$1)) with filledcurves fs transparent solid 0.15 noborder lc rgb '" << colours[m]
                    << "' notitle";
    }
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      gp << ", '' using 1:" << 2 + m << " with lines lw 2 lc rgb '" << colours[m] << "' title '" << kFig8Models[m].label
         << " (simulated)'";
      gp_efficiency << ", '' using 1:(100*$" << 2 + m << "/(" << c.serial_fps << "*$1)) with lines lw 2 lc rgb '"
                    << colours[m] << "' title '" << kFig8Models[m].label << " (simulated)'";
    }
    for (std::size_t m = 0; m < kFig8ModelCount; ++m) {
      gp << ", '' using 1:" << 2 + kFig8ModelCount + m << " with points pt " << 5 + 2 * m << " ps 1.4 lc rgb '"
         << colours[m] << "' title '" << kFig8Models[m].label << " (measured)'";
      gp_efficiency << ", '' using 1:(100*$" << 2 + kFig8ModelCount + m << "/(" << c.serial_fps
                    << "*$1)) with points pt " << 5 + 2 * m << " ps 1.4 lc rgb '" << colours[m] << "' title '"
                    << kFig8Models[m].label << " (measured)'";
    }
    gp << '\n';
    gp_efficiency << '\n';
  }
  gp << gp_efficiency.str() << "unset multiplot\n";
  run.dir().write_gnuplot(name + ".gp", {1500, 900}, gp.str());
}

}  // namespace

void write_fig8(const std::vector<SceneCurves>& all, PaperRun& run, const std::string& name) {
  VerdictTally tally;
  bool measured = false;
  for (const SceneCurves& c : all) {
    measured = measured || !c.meas_ps.empty();
    for (const auto& both : c.meas_verdicts) {
      for (const JudgedComparison& j : both) tally.add(j);
    }
  }
  report::Json js = run.document(kSchemaVersion, name, measured ? "measured and simulated" : "simulated");
  js["scenes"] = report::Json::array();
  for (const SceneCurves& c : all) js["scenes"].push_back(scene_json(c));
  const ErrorBand band = error_band(run);
  if (!run.options().validation.empty() && !(band.pct > 0)) {
    std::cerr << kPaperProgram << ": WARNING: " << band.source << '\n';
  }
  write_plot(all, run, name, band);
  const std::string md = markdown(all, run, tally, band);
  run.dir().write(name + ".md", md);
  run.dir().write(name + ".csv", csv_table(all).csv());
  run.dir().write_json(name + ".json", js);
  run.plot(name + ".gp");
  std::cout << md << "\nwrote " << run.dir().file(name + ".md").string() << ", .csv, .json, .png\n";
  if (tally.unreliable) {
    std::cerr << kPaperProgram << ": WARNING: noisy machine: " << tally.unreliable << " of " << tally.verdicts
              << " measured verdicts unreliable (reasons in " << name << ".md)\n";
  }
}

}  // namespace frontsteal::papers
