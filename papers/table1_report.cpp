// table1_report.cpp — Table 1: measure, simulate, write (table1_report.hpp).
#include "papers/table1_report.hpp"

#include <iostream>
#include <sstream>

#include "papers/measured_noise.hpp"
#include "papers/paper_numbers.hpp"
#include "reporting/table.hpp"

namespace frontsteal::papers {

namespace {

// table1.json's schema (docs/results-schema.md). 2: the common header of reporting/ (schema 1, by hand, had
// no schema_version, program or kind); every key of schema 1 is kept.
constexpr int kSchemaVersion = 2;

struct Row {
  std::string scene;
  std::string paper_model;  // the paper's model this stand-in pairs with ("" when --scenes)
  std::size_t surfaces = 0;
  MeasuredRun meas_rr, meas_sp;
  SimulatedRun sim_rr_m, sim_sp_m, sim_rr, sim_sp;  // at P = cores and at P = 25
  JudgedComparison spatial_vs_rr;
  std::string noise_line;
  report::Json noise;
};

Row measure_and_simulate(PaperRun& run, const std::string& scene, std::size_t index) {
  const Options& o = run.options();
  const WorkerId pm = hardware_cores(), ps = kPaperTable1Processors;
  PathWorkload wl = run.load(scene);
  Row r;
  r.scene = scene;
  r.paper_model = index < kPaperTable1.size() && o.scenes.empty() ? std::string(kPaperTable1[index].model) : "";
  r.surfaces = wl.surfaces();
  MeasureOptions mo{.schedulers = {"round-robin", "spatial-annealing"},
                    .threads = {pm},
                    .repeats = o.repeats,
                    .seed = o.seed,
                    .progress = run.sink()};
  run.say("table1 " + scene + ": measuring round-robin and spatial-annealing at P=" + std::to_string(pm));
  MeasurementNoise sampled;
  const auto meas = measure_schedulers(wl, mo, nullptr, &sampled);
  r.meas_rr = meas[0];
  r.meas_sp = meas[1];
  const MeasuredNoise noise(sampled);
  r.spatial_vs_rr = noise.judge(r.meas_sp, r.meas_rr);
  r.noise_line = noise.line();
  r.noise = noise.json();
  const CostTrace t = run.record_trace(wl);
  const Overheads& ov = run.overheads();
  run.say("table1 " + scene + ": simulating at P=" + std::to_string(pm) + " and P=" + std::to_string(ps));
  r.sim_rr_m = simulate_static(t, ov, pm, false, o.seed);
  r.sim_sp_m = simulate_static(t, ov, pm, true, o.seed);
  r.sim_rr = simulate_static(t, ov, ps, false, o.seed);
  r.sim_sp = simulate_static(t, ov, ps, true, o.seed);
  return r;
}

const std::vector<report::Column> kStandInColumns = {{"paper_model", "stand-in for", false},
                                                     {"scene", "scene", false},
                                                     {"round_robin_fps", "round robin frames/s"},
                                                     {"round_robin_utilization_pct", "utilization"},
                                                     {"spatial_fps", "spatial frames/s"},
                                                     {"spatial_utilization_pct", "utilization"},
                                                     {"gain", "gain"}};

report::Table paper_table() {
  report::Table t({{"model", "model", false},
                   {"surfaces", "surfaces"},
                   {"round_robin_fps", "round robin frames/s"},
                   {"round_robin_utilization_pct", "utilization"},
                   {"partition_fps", "partition frames/s"},
                   {"partition_utilization_pct", "utilization"},
                   {"gain", "gain"}});
  for (const auto& p : kPaperTable1) {
    t.add_row({std::string(p.model), p.surfaces, report::Cell::fixed(p.round_robin_fps, 2),
               report::Cell::shown_as(fixed(p.round_robin_utilization_pct, 1) + "%", p.round_robin_utilization_pct),
               report::Cell::fixed(p.partition_fps, 2),
               report::Cell::shown_as(fixed(p.partition_utilization_pct, 1) + "%", p.partition_utilization_pct),
               pct_change(p.partition_fps / p.round_robin_fps)});
  }
  return t;
}

// One of our three tables: frames/s and utilization of round robin and spatial, as `pick` gives them.
template <class Pick>
report::Table stand_in_table(const std::vector<Row>& rows, Pick pick) {
  report::Table t(kStandInColumns);
  for (const Row& r : rows) {
    const auto [a, b] = pick(r);
    t.add_row({r.paper_model.empty() ? std::string("-") : r.paper_model, "`" + r.scene + "`",
               report::Cell::fixed(a.frames_per_s, 2),
               report::Cell::shown_as(fixed(a.utilization_pct, 1) + "%", a.utilization_pct),
               report::Cell::fixed(b.frames_per_s, 2),
               report::Cell::shown_as(fixed(b.utilization_pct, 1) + "%", b.utilization_pct),
               pct_change(b.frames_per_s / a.frames_per_s)});
  }
  return t;
}

// The measured comparison, repeat by repeat, with CPU time and the noise monitor's line.
report::Table verdict_table(const std::vector<Row>& rows) {
  report::Table t({{"scene", "scene", false},
                   {"spatial_vs_round_robin", "spatial / round robin [95% CI] verdict", false},
                   {"round_robin_cpu_pct", "cpu round robin"},
                   {"spatial_cpu_pct", "cpu spatial"}});
  for (const Row& r : rows) {
    t.add_row({"`" + r.scene + "`", r.spatial_vs_rr.text(),
               report::Cell::shown_as(fixed(r.meas_rr.cpu_pct, 1) + "%", r.meas_rr.cpu_pct),
               report::Cell::shown_as(fixed(r.meas_sp.cpu_pct, 1) + "%", r.meas_sp.cpu_pct)});
  }
  return t;
}

std::string markdown(const std::vector<Row>& rows, const PaperRun& run, const VerdictTally& tally) {
  const Options& o = run.options();
  const WorkerId pm = hardware_cores(), ps = kPaperTable1Processors;
  using Pair = std::pair<const MeasuredRun&, const MeasuredRun&>;
  using SimPair = std::pair<const SimulatedRun&, const SimulatedRun&>;
  std::ostringstream md;
  md << "# Table 1: static load distribution, round robin vs spatial partition\n\n"
     << run.stamp() << "\n\n"
     << "The paper's models (parts of a submarine storage and handling system) are not available; ours are "
        "**procedural stand-ins** with the same surface counts (`plant:N`, tessellate/scene_generator.hpp), "
        "tessellated along the main job's camera path ("
     << o.frames
     << " frames: an orbit, then a zoom into a "
        "corner). The paper's partition is a graph partition by simulated annealing; ours is `spatial-annealing` "
        "(schedulers/static_assignment.hpp). Utilization = busy / (wall × P).\n\n"
     << "## The paper (Pixel-Planes 5, " << ps << " i860 Graphics Processors at 40 MHz)\n\n"
     << paper_table().markdown();
  md << "\n## Ours, SIMULATED at P = " << ps
     << " (the paper's processor count; trace-driven, costs of this machine)\n\n"
     << stand_in_table(rows, [](const Row& r) {
          return SimPair{r.sim_rr, r.sim_sp};
        }).markdown();
  md << "\n## Ours, MEASURED at P = " << pm << " (this machine)\n\n"
     << stand_in_table(rows, [](const Row& r) {
          return Pair{r.meas_rr, r.meas_sp};
        }).markdown();
  md << "\n## Ours, SIMULATED at P = " << pm << " (to validate the simulator against the measured rows)\n\n"
     << stand_in_table(rows, [](const Row& r) {
          return SimPair{r.sim_rr_m, r.sim_sp_m};
        }).markdown();
  md << "\nSimulator error at P = " << pm << " (frames/s, simulated vs measured): ";
  for (const Row& r : rows) {
    md << "`" << r.scene << "` round robin " << pct_change(r.sim_rr_m.frames_per_s / r.meas_rr.frames_per_s)
       << ", spatial " << pct_change(r.sim_sp_m.frames_per_s / r.meas_sp.frames_per_s) << "; ";
  }
  md << "\n\nMeasured at P = " << pm
     << ", round by round: the path-time ratio spatial / round robin [95 % "
        "interval] and verdict ("
     << comparison_method(o.repeats)
     << "), and the workers' CPU time over wall × P "
        "(below utilization's busy share when a worker lost its CPU):\n\n"
     << verdict_table(rows).markdown() << '\n';
  for (const Row& r : rows) md << "`" << r.scene << "`: " << r.noise_line << "\n";
  if (tally.unreliable) md << '\n' << tally.warning();
  md << "\nAbsolute frames/s are not comparable: one core here tessellates these stand-ins far faster than "
        "an i860 did the paper's models. Compare utilization and the gain of the partition over round robin.\n\n"
     << "![Table 1](table1.png)\n";
  return md.str();
}

// Long form: the paper's rows, then per scene measured and simulated at P = cores, simulated at P = 25.
report::Table csv_table(const std::vector<Row>& rows) {
  const WorkerId pm = hardware_cores(), ps = kPaperTable1Processors;
  report::Table t({{"source", "source", false},
                   {"scene", "scene", false},
                   {"paper_model", "paper model", false},
                   {"surfaces", "surfaces"},
                   {"workers", "workers"},
                   {"scheduler", "scheduler", false},
                   {"frames_per_s", "frames/s"},
                   {"utilization_pct", "utilization (%)"}});
  for (const auto& p : kPaperTable1) {
    t.add_row({"paper", "", std::string(p.model), p.surfaces, ps, "round-robin",
               report::Cell::fixed(p.round_robin_fps, 2), report::Cell::fixed(p.round_robin_utilization_pct, 1)});
    t.add_row({"paper", "", std::string(p.model), p.surfaces, ps, "graph-partition",
               report::Cell::fixed(p.partition_fps, 2), report::Cell::fixed(p.partition_utilization_pct, 1)});
  }
  for (const Row& r : rows) {
    auto line = [&](const char* source, WorkerId p, const char* scheduler, double fps, double u) {
      t.add_row({source, r.scene, r.paper_model, static_cast<std::uint64_t>(r.surfaces), p, scheduler,
                 report::Cell::fixed(fps, 2), report::Cell::fixed(u, 1)});
    };
    line("measured", pm, "round-robin", r.meas_rr.frames_per_s, r.meas_rr.utilization_pct);
    line("measured", pm, "spatial-annealing", r.meas_sp.frames_per_s, r.meas_sp.utilization_pct);
    line("simulated", pm, "round-robin", r.sim_rr_m.frames_per_s, r.sim_rr_m.utilization_pct);
    line("simulated", pm, "spatial-annealing", r.sim_sp_m.frames_per_s, r.sim_sp_m.utilization_pct);
    line("simulated", ps, "round-robin", r.sim_rr.frames_per_s, r.sim_rr.utilization_pct);
    line("simulated", ps, "spatial-annealing", r.sim_sp.frames_per_s, r.sim_sp.utilization_pct);
  }
  return t;
}

report::Json json(const std::vector<Row>& rows, const PaperRun& run) {
  const WorkerId pm = hardware_cores(), ps = kPaperTable1Processors;
  report::Json js = run.document(kSchemaVersion, "table1", "measured and simulated");
  js["rows"] = report::Json::array();
  for (const Row& r : rows) {
    auto cell = [](double fps, double u) { return report::Json{{"fps", fps}, {"utilization_pct", u}}; };
    report::Json measured = {{"workers", pm},
                             {"round_robin", cell(r.meas_rr.frames_per_s, r.meas_rr.utilization_pct)},
                             {"spatial", cell(r.meas_sp.frames_per_s, r.meas_sp.utilization_pct)}};
    measured["round_robin"]["cpu_pct"] = r.meas_rr.cpu_pct;
    measured["round_robin"]["path_ms_per_repeat"] = r.meas_rr.path_ms;
    measured["spatial"]["cpu_pct"] = r.meas_sp.cpu_pct;
    measured["spatial"]["path_ms_per_repeat"] = r.meas_sp.path_ms;
    measured["spatial_vs_round_robin"] = r.spatial_vs_rr.json();
    measured["noise"] = r.noise;
    js["rows"].push_back({{"scene", r.scene},
                          {"surfaces", r.surfaces},
                          {"measured", measured},
                          {"simulated",
                           {{"workers", ps},
                            {"round_robin", cell(r.sim_rr.frames_per_s, r.sim_rr.utilization_pct)},
                            {"spatial", cell(r.sim_sp.frames_per_s, r.sim_sp.utilization_pct)}}}});
  }
  return js;
}

// Plot: utilization, grouped by model: paper (P = 25), simulated (P = 25), measured (P = cores).
void write_plot(const std::vector<Row>& rows, PaperRun& run) {
  const WorkerId pm = hardware_cores(), ps = kPaperTable1Processors;
  std::ostringstream dat, gp;
  dat << "# model paper_rr paper_part sim_rr sim_spatial meas_rr meas_spatial\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const bool paired = !r.paper_model.empty();
    dat << '"' << (paired ? r.paper_model + " / " : std::string()) << r.scene << "\" "
        << (paired ? kPaperTable1[i].round_robin_utilization_pct : 0) << ' '
        << (paired ? kPaperTable1[i].partition_utilization_pct : 0) << ' ' << r.sim_rr.utilization_pct << ' '
        << r.sim_sp.utilization_pct << ' ' << r.meas_rr.utilization_pct << ' ' << r.meas_sp.utilization_pct << '\n';
  }
  gp << "set output 'table1.png'\n"
     << "set title \"Table 1: utilization, round robin vs spatial partition\\n"
     << machine_line() << ", commit " << run.commit()
     << "\"\nset style data histograms\nset style histogram clustered gap 1\n"
     << "set style fill solid 0.85 border -1\nset boxwidth 0.9\nset yrange [0:105]\nset ylabel 'utilization (%)'\n"
     << "set key outside right top\nset grid ytics\n"
     << "plot 'table1.dat' using 2:xtic(1) title 'paper: round robin (P=25, Pixel-Planes 5)' lc rgb '#9ecae1', "
        "'' using 3 title 'paper: graph partition (P=25)' lc rgb '#3182bd', "
        "'' using 4 title 'SIMULATED: round robin (P="
     << ps
     << ")' lc rgb '#fdae6b', "
        "'' using 5 title 'SIMULATED: spatial (P="
     << ps
     << ")' lc rgb '#e6550d', "
        "'' using 6 title 'MEASURED: round robin (P="
     << pm
     << ")' lc rgb '#a1d99b', "
        "'' using 7 title 'MEASURED: spatial (P="
     << pm << ")' lc rgb '#31a354'\n";
  run.dir().write("table1.dat", dat.str());
  run.dir().write_gnuplot("table1.gp", {1100, 620}, gp.str());
}

}  // namespace

int run_table1(PaperRun& run) {
  run.overheads();  // calibrated first, as before the split: the microbenchmarks run on a machine at rest
  std::vector<std::string> scenes = run.options().scenes;
  if (scenes.empty()) {
    for (const auto& r : kPaperTable1) scenes.push_back("plant:" + std::to_string(r.surfaces));
  }
  std::vector<Row> rows;
  VerdictTally tally;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    rows.push_back(measure_and_simulate(run, scenes[i], i));
    tally.add(rows.back().spatial_vs_rr);
  }
  const std::string md = markdown(rows, run, tally);
  write_plot(rows, run);
  run.dir().write("table1.md", md);
  run.dir().write("table1.csv", csv_table(rows).csv());
  run.dir().write_json("table1.json", json(rows, run));
  run.plot("table1.gp");
  std::cout << md << "\nwrote " << run.dir().file("table1.md").string() << ", .csv, .json, .png\n";
  if (tally.unreliable) {
    std::cerr << kPaperProgram << ": WARNING: noisy machine: " << tally.unreliable << " of " << tally.verdicts
              << " measured verdicts unreliable (reasons in table1.md)\n";
  }
  return 0;
}

}  // namespace frontsteal::papers
