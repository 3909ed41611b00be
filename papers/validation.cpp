// validation.cpp — predictions against the main job's measurements (validation.hpp).
#include "papers/validation.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "measure/machine_info.hpp"
#include "reporting/json.hpp"
#include "schedulers/static_assignment.hpp"

namespace frontsteal::papers {

MeasuredSet read_measured_set(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  report::Json doc;
  try {
    doc = report::Json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": not JSON (" + e.what() + ")");
  }
  auto need = [&](const report::Json& j, const char* key) -> const report::Json& {
    if (!j.contains(key)) throw std::runtime_error(file.string() + ": no '" + key + "'");
    return j.at(key);
  };
  MeasuredSet s;
  s.name = name;
  s.path = need(doc, "path").get<std::string>();
  s.scene = need(doc, "scene").get<std::string>();
  s.machine = need(doc, "machine").get<std::string>();
  const report::Json& inter = need(doc, "interference");
  s.interference = need(inter, "on").get<bool>();
  if (s.interference) s.co_runner_share = need(inter, "co_runner_core_share_measured").get<double>();
  s.serial_ms = need(need(doc, "serial"), "path_ms").get<double>();
  for (const report::Json& l : doc.value("limits", report::Json::array())) {
    if (!l.contains("copy_relative_time")) continue;
    std::vector<double>& t = s.limit_copy_time[l.at("workers").get<WorkerId>()];
    for (const report::Json& v : l.at("copy_relative_time")) t.push_back(v.get<double>());
  }
  for (const report::Json& r : need(doc, "results")) {
    MeasuredCell c;
    c.scheduler = need(r, "scheduler").get<std::string>();
    c.workers = need(r, "workers").get<WorkerId>();
    c.path_ms = need(r, "path_ms").get<double>();
    c.spread_pct = need(r, "path_spread_pct").get<double>();
    auto ratio = [](const report::Json& row, const char* key) {
      MeasuredRatio m;
      if (!row.contains(key) || !row[key].is_object() || !row[key].contains("ci95_low") || row[key]["ratio"].is_null())
        return m;
      m.ratio = row[key]["ratio"].get<double>();
      m.low = row[key]["ci95_low"].get<double>();
      m.high = row[key]["ci95_high"].get<double>();
      m.valid = true;
      return m;
    };
    c.vs_serial = ratio(r, "vs_serial");
    c.vs_queue = ratio(r, "vs_queue_mutex");
    if (r.contains("account") && r["account"].is_object()) {
      const report::Json& acc = r["account"];
      MeasuredAccount m;
      for (const auto& [term, share] : need(acc, "shares").items()) m.shares[term] = share.get<double>();
      m.claim_per_item_ns = need(acc, "claim_per_item_ns").get<double>();
      m.checks_per_item_ns = need(acc, "checks_per_item_ns").get<double>();
      m.frames = need(acc, "frames").get<std::uint64_t>();
      if (acc.contains("inflation") && acc["inflation"].is_object())
        m.inflation = acc["inflation"]["factor"].get<double>();
      for (const report::Json& w : need(r, "per_worker")) {
        m.wake_ms.push_back(w.value("wake_ms", 0.0));
        m.termination_ms.push_back(w.value("termination_ms", 0.0));
      }
      c.account = std::move(m);
    }
    s.cells.push_back(c);
  }
  return s;
}

std::vector<MeasuredSet> read_study(const std::filesystem::path& study) {
  std::vector<MeasuredSet> sets;
  for (const auto& entry : std::filesystem::directory_iterator(study)) {
    const auto file = entry.path() / "frontsteal.json";
    if (entry.is_directory() && std::filesystem::exists(file)) {
      sets.push_back(read_measured_set(file, entry.path().filename().string()));
    }
  }
  std::sort(sets.begin(), sets.end(), [](const MeasuredSet& a, const MeasuredSet& b) { return a.name < b.name; });
  return sets;
}

std::map<std::string, double> MeasuredAccount::shares_with_off_cpu() const {
  std::map<std::string, double> out = shares;
  const auto off = shares.find("off_cpu");
  if (off == shares.end() || off->second <= 0) return out;
  double span = 0;
  for (const char* t : {"work", "claim", "checks", "search", "steal", "wait", "termination"}) {
    if (shares.count(t)) span += shares.at(t);
  }
  if (span <= 0) return out;
  for (const char* t : {"work", "claim", "checks", "search", "steal", "wait", "termination"}) {
    if (out.count(t)) out[t] *= (span + off->second) / span;
  }
  out["off_cpu"] = 0;
  return out;
}

std::optional<Model> model_of(const std::string& scheduler) {
  if (scheduler == "round-robin") return Model::static_list;
  if (scheduler == "queue-mutex") return Model::queue;
  if (scheduler == "stealing/Fenced") return Model::stealing;
  if (scheduler == "chase-lev") return Model::chase_lev;
  return std::nullopt;
}

std::vector<double> slowdown_of(const MeasuredSet& set, WorkerId workers) {
  std::vector<double> f(workers, 1.0);
  if (set.interference && set.co_runner_share > 0 && set.co_runner_share < 1) f[0] = 1.0 / (1.0 - set.co_runner_share);
  return f;
}

double predict_path_ms(const CostTrace& trace, double trace_scale, const Overheads& o, const std::string& scheduler,
                       WorkerId workers, const std::vector<double>& slowdown, std::uint64_t seed) {
  const std::optional<Model> m = model_of(scheduler);
  if (!m) throw std::invalid_argument("no simulator model for " + scheduler);
  CostTrace scaled = trace;
  for (auto& frame : scaled.cost_ns) {
    for (double& c : frame) c *= trace_scale;
  }
  const sched::Assignment rr = sched::round_robin_assignment(static_cast<ItemId>(trace.surfaces()), workers);
  const SimulationOptions so{
      .model = *m, .workers = workers, .assignment = &rr, .seed = seed, .worker_slowdown = slowdown};
  const SimulatedRun run = simulate(scaled, o, so);
  if (run.audit_failures) throw std::logic_error("validation: the simulation of " + scheduler + " failed its audit");
  return run.path_ns / 1e6;
}

double error_pct(double predicted, double measured) {
  if (!(measured > 0)) throw std::invalid_argument("error_pct: the measured value must be positive");
  return 100.0 * (predicted - measured) / measured;
}

double interval_error_pct(double predicted, const MeasuredRatio& m) {
  if (predicted >= m.low && predicted <= m.high) return 0;
  return error_pct(predicted, predicted < m.low ? m.low : m.high);
}

ErrorSummary summarize_errors(const std::vector<double>& e) {
  if (e.empty()) throw std::invalid_argument("summarize_errors: no cells");
  ErrorSummary s;
  s.cells = e.size();
  std::vector<double> abs;
  double sum = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    abs.push_back(std::fabs(e[i]));
    sum += e[i];
    if (std::fabs(e[i]) > s.worst_abs_pct) {
      s.worst_abs_pct = std::fabs(e[i]);
      s.worst_index = i;
    }
  }
  s.median_abs_pct = median(abs);
  s.mean_signed_pct = sum / static_cast<double>(e.size());
  return s;
}

Overheads without_new_terms(Overheads o) {
  o.affinity_penalty = 0;
  o.lock_wake_ns = 0;
  o.wake_skew_ns = 0;
  return o;
}

}  // namespace frontsteal::papers
