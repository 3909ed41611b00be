// paper_run.cpp — PaperRun and the helpers every artifact shares (paper_run.hpp).
#include "papers/paper_run.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "measure/machine_info.hpp"
#include "reporting/table.hpp"
#include "schedulers/static_assignment.hpp"

namespace frontsteal::papers {

namespace sc = frontsteal::sched;

std::string machine_line() { return machine_description(); }

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::gmtime(&now));
  return buf;
}

std::string fixed(double v, int digits) { return report::fixed_text(v, digits); }

std::string pct_change(double ratio) { return (ratio >= 1 ? "+" : "") + fixed(100.0 * (ratio - 1.0), 1) + "%"; }

std::string short_name(const std::string& scene) {
  std::string s = scene;
  std::replace(s.begin(), s.end(), ':', '-');
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

std::vector<WorkerId> simulated_ps(WorkerId max_p) {
  std::vector<WorkerId> ps;
  for (WorkerId p = 1; p <= max_p; p = p < 16 ? p + 1 : p < 32 ? p + 4 : p + 8) ps.push_back(p);
  if (ps.back() != max_p) ps.push_back(max_p);
  return ps;
}

std::vector<WorkerId> measured_ps() {
  std::vector<WorkerId> ps;
  for (WorkerId p = 1; p <= hardware_cores(); ++p) ps.push_back(p);
  return ps;
}

PaperRun::PaperRun(Options options, std::string commit, std::string data_dir)
    : o_(std::move(options)),
      commit_(std::move(commit)),
      data_dir_(std::move(data_dir)),
      start_(std::chrono::steady_clock::now()) {}

std::string PaperRun::stamp() const {
  return "Machine: " + machine_line() + ". Commit " + commit_ + ", run " + today() + ".";
}

void PaperRun::say(const std::string& line) const {
  if (o_.quiet) return;
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "[%6.1fs] %s\n", s, line.c_str());
}

std::function<void(const std::string&)> PaperRun::sink() const {
  return [this](const std::string& l) { say("  " + l); };
}

const report::ResultsDir& PaperRun::dir() {
  if (!dir_) dir_.emplace(kPaperProgram, o_.out);
  return *dir_;
}

void PaperRun::plot(std::string_view script) {
  if (o_.plot) dir().plot(script);
}

report::Json PaperRun::document(int schema_version, std::string_view artifact, std::string_view kind) const {
  report::Json doc = report::document(kPaperProgram, schema_version, kind, commit_);
  doc["artifact"] = artifact;
  doc["machine"] = machine_line();
  doc["date"] = today();
  return doc;
}

const Overheads& PaperRun::overheads() {
  if (overheads_) return *overheads_;
  if (!o_.calibration.empty()) {
    say("calibration: reading " + o_.calibration);
    return overheads_.emplace(read_overheads(o_.calibration));
  }
  overheads_ = calibrate(machine_line(), commit_, sink());
  calibrated_here_ = true;
  write_overheads(*overheads_, dir().file("calibration.txt"));
  dir().write("calibration.md",
              "# Simulator costs (measured by microbenchmarks)\n\n" + stamp() + "\n\n" + describe(*overheads_));
  return *overheads_;
}

PathWorkload PaperRun::load(const std::string& scene) const {
  say("scene " + scene + ": generating and preparing");
  WorkloadOptions wo;
  wo.scene = scene;
  wo.frames = o_.frames;
  wo.data_dir = data_dir_;
  return PathWorkload(wo);
}

CostTrace PaperRun::record_trace(PathWorkload& wl) {
  say("trace: " + std::to_string(o_.passes) + " serial passes over " + std::to_string(wl.frames()) + " frames");
  CostTrace t = record_cost_trace(wl, o_.passes, machine_line(), commit_);
  const auto file = dir().file("trace-" + short_name(wl.options().scene) + ".txt");
  write_cost_trace(t, file);
  say("trace: wrote " + file.string() + " (serial path " + fixed(t.path_cost_ns() / 1e6, 1) + " ms)");
  return t;
}

SimulatedRun simulate_static(const CostTrace& t, const Overheads& ov, WorkerId p, bool spatial, std::uint64_t seed) {
  const sc::WorkloadHints hints{t.centres, t.estimates};
  const auto n = static_cast<ItemId>(t.surfaces());
  sc::AnnealingOptions ao;
  ao.seed = seed;
  const sc::Assignment a = spatial ? sc::annealed_assignment(n, p, hints, ao) : sc::round_robin_assignment(n, p);
  SimulationOptions so{.model = Model::static_list, .workers = p, .assignment = &a, .seed = seed};
  return simulate(t, ov, so);
}

SimulatedRun simulate_model(const CostTrace& t, const Overheads& ov, Model m, WorkerId p, std::uint64_t seed) {
  if (m == Model::static_list) return simulate_static(t, ov, p, true, seed);
  return simulate(t, ov, {.model = m, .workers = p, .seed = seed});
}

void require_audit(const SimulatedRun& r, const std::string& what) {
  if (r.audit_failures) throw std::runtime_error("simulator audit failed: " + what);
}

int run_calibrate(PaperRun& run) {
  const Overheads& ov = run.overheads();
  std::cout << "# Simulator costs (measured by microbenchmarks)\n\n"
            << run.stamp() << "\n\n"
            << describe(ov) << "\nwrote " << (std::filesystem::path(run.options().out) / "calibration.txt").string()
            << ", calibration.md\n";
  return 0;
}

int run_trace(PaperRun& run) {
  const Options& o = run.options();
  PathWorkload wl = run.load(o.scene);
  const CostTrace t = record_cost_trace(wl, o.passes, machine_line(), run.commit());
  const std::string file = o.trace.empty() ? run.dir().file("trace-" + short_name(o.scene) + ".txt").string() : o.trace;
  write_cost_trace(t, file);
  std::cout << "wrote " << file << ": " << t.surfaces() << " surfaces x " << t.frames() << " frames, serial path "
            << fixed(t.path_cost_ns() / 1e6, 1) << " ms\n";
  return 0;
}

}  // namespace frontsteal::papers
