// rma_simulator_io.cpp — the simulator's inputs and outputs (rma_simulator.hpp): latencies from a calibration
// file, the latencies as JSON for the SIMULATED output, and the efficiency plot.
#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "distributed/calibration_operations.hpp"
#include "distributed/rma_simulator.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::mpi::sim {
namespace {

namespace ops = calibration_ops;

// The median of `name`, or nothing in a calibration written before that operation was timed.
std::optional<double> optional_operation_ns(const report::Json& doc, std::string_view name) {
  for (const report::Json& op : doc.at("operations")) {
    if (op.at("operation").get<std::string>() == name) return op.at("median_ns").get<double>();
  }
  return std::nullopt;
}

double operation_ns(const report::Json& doc, const std::string& path, std::string_view name) {
  if (const std::optional<double> ns = optional_operation_ns(doc, name)) return *ns;
  throw std::runtime_error(path + ": no operation '" + std::string(name) + "' (run frontsteal-mpi --calibrate --json)");
}

}  // namespace

const char* to_string(Scheduler s) noexcept {
  switch (s) {
    case Scheduler::kRma: return "rma";
    case Scheduler::kRequest: return "request";
    case Scheduler::kCentral: return "central";
    case Scheduler::kStatic: return "static";
    case Scheduler::kStaticSpace: return "static-space";
    case Scheduler::kHier: return "hier";
    case Scheduler::kHierSeeded: return "hier-seeded";
  }
  return "?";
}

Latencies latencies_from_calibration(const std::string& path) {
  const report::Json doc = report::read_document(path, "calibration file");
  if (doc.value("contents", "") != "calibration") throw std::runtime_error(path + ": not a calibration (contents)");
  Latencies l;
  l.get = operation_ns(doc, path, ops::kGet);
  l.put = operation_ns(doc, path, ops::kPut);
  l.cas = operation_ns(doc, path, ops::kCompareAndSwap);
  l.fetch_op = operation_ns(doc, path, ops::kFetchAndOp);
  l.ping_pong = operation_ns(doc, path, ops::kPingPong);
  l.claim = operation_ns(doc, path, ops::kClaim);
  l.poll = operation_ns(doc, path, ops::kRequestPoll);
  l.progress_call = operation_ns(doc, path, ops::kProgressCall);
  const std::string osc = doc.value("osc_requested", "");
  l.needs_target_progress = !doc.value("one_node", true) || (!osc.empty() && osc.find("sm") == std::string::npos);
  const std::optional<double> burst = optional_operation_ns(doc, ops::kFetchAndOpPipelined);
  l.atomic_service = l.needs_target_progress && burst ? *burst : std::max(l.fetch_op - l.get, 50.0);
  l.source = path + (l.needs_target_progress ? " (transport without asynchronous target progress)"
                                             : " (shared memory, osc/sm)");
  return l;
}

report::Json latencies_json(const Latencies& l) {
  return {{"source", l.source},
          {"get_ns", l.get},
          {"put_ns", l.put},
          {"compare_and_swap_ns", l.cas},
          {"fetch_and_op_ns", l.fetch_op},
          {"ping_pong_ns", l.ping_pong},
          {"owner_claim_ns", l.claim},
          {"request_poll_ns", l.poll},
          {"owner_progress_call_ns", l.progress_call},
          {"atomic_service_ns", l.atomic_service},
          {"needs_target_progress", l.needs_target_progress},
          {"progress_every_ns", l.progress_every},
          {"local_claim_ns_assumed", l.local_claim},
          {"local_steal_ns_assumed", l.local_steal},
          {"rank_lock_ns_assumed", l.rank_lock}};
}

void write_efficiency_plot(const std::string& dir_name, const report::Json& rows, const std::string& subtitle) {
  const report::ResultsDir dir("frontsteal-mpi-simulate", dir_name);
  std::map<std::string, std::vector<std::pair<int, double>>> lines;  // "tcp rma" -> (ranks, efficiency)
  std::vector<std::string> order;
  for (const report::Json& row : rows) {
    const int threads = row.value("threads", 1);
    const std::string key = row.at("latencies").get<std::string>() + " " + row.at("scheduler").get<std::string>() +
                            (threads > 1 ? " x" + std::to_string(threads) + " threads" : "");
    if (!lines.count(key)) order.push_back(key);
    lines[key].emplace_back(row.at("ranks").get<int>(), row.at("efficiency").get<double>());
  }
  std::ostringstream dat;
  for (const std::string& key : order) {
    dat << '"' << key << "\"\n";
    for (const auto& [ranks, eff] : lines[key]) dat << ranks << ' ' << eff << '\n';
    dat << "\n\n";
  }
  dir.write("simulated-efficiency.dat", dat.str());
  std::ostringstream gp;
  gp << "set output 'simulated-efficiency.png'\n"
     << "set title \"SIMULATED efficiency = work / (ranks x threads x time), not a measurement\\n"
     << report::gnuplot_text(subtitle) << "\"\n"
     << "set logscale x 2\nset xlabel 'ranks'\nset ylabel 'efficiency'\nset yrange [0:1.05]\nset grid\n"
     << "set key outside right top\n"
     << "plot for [i=0:" << (order.empty() ? 0 : order.size() - 1) << "] 'simulated-efficiency.dat' index i "
     << "using 1:2 with linespoints lt 1+i%4 dt 1+i/4 pt 1+i title columnheader(1)\n";
  dir.write_gnuplot("simulated-efficiency.gp", {1100, 640, "font 'sans,10' noenhanced"}, gp.str());
  dir.plot("simulated-efficiency.gp");
}

void write_loss_plot(const std::string& dir_name, const report::Json& losses, const std::string& subtitle) {
  const report::ResultsDir dir("frontsteal-mpi-simulate", dir_name);
  static constexpr std::array<const char*, 7> kParts{"work", "claims", "local_steals", "remote_steals",
                                                     "idle", "tail",   "barrier"};
  std::ostringstream dat;
  dat << "run";
  for (const char* part : kParts) dat << ' ' << part;
  dat << '\n';
  for (const report::Json& l : losses) {
    dat << '"' << l.at("latencies").get<std::string>() << ' ' << l.value("scheduler", std::string("hier")) << ' '
        << l.at("ranks").get<int>() << 'x' << l.at("threads").get<int>() << '"';
    for (const char* part : kParts) dat << ' ' << l.at(part).get<double>();
    dat << '\n';
  }
  dir.write("hier-loss-account.dat", dat.str());
  std::ostringstream gp;
  gp << "set output 'hier-loss-account.png'\n"
     << "set title \"SIMULATED: where the workers' time went (share of ranks x threads x time), not a measurement\\n"
     << report::gnuplot_text(subtitle) << "\"\n"
     << "set style data histograms\nset style histogram rowstacked\nset style fill solid 0.8 border -1\n"
     << "set boxwidth 0.7\nset yrange [0:1.05]\nset ylabel 'share of the workers time'\nset grid y\n"
     << "set xtics rotate by -30\nset key outside right top\n"
     << "plot for [i=2:" << kParts.size() + 1 << "] 'hier-loss-account.dat' using i:xtic(1) title columnheader(i)\n";
  dir.write_gnuplot("hier-loss-account.gp", {1100, 640, "font 'sans,10' noenhanced"}, gp.str());
  dir.plot("hier-loss-account.gp");
}

}  // namespace frontsteal::mpi::sim
