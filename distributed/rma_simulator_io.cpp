// rma_simulator_io.cpp — the simulator's inputs and labels (rma_simulator.hpp): latencies from a calibration
// file, and the latencies as JSON for the SIMULATED output.
#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "distributed/rma_simulator.hpp"

namespace frontsteal::mpi::sim {
namespace {

double operation_ns(const report::Json& doc, const std::string& path, const std::string& prefix) {
  for (const report::Json& op : doc.at("operations")) {
    if (op.at("operation").get<std::string>().rfind(prefix, 0) == 0) return op.at("median_ns").get<double>();
  }
  throw std::runtime_error(path + ": no operation starting with '" + prefix + "' (run frontsteal-mpi --calibrate --json)");
}

}  // namespace

const char* to_string(Scheduler s) noexcept {
  switch (s) {
    case Scheduler::kRma: return "rma";
    case Scheduler::kRequest: return "request";
    case Scheduler::kCentral: return "central";
    case Scheduler::kStatic: return "static";
  }
  return "?";
}

Latencies latencies_from_calibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read calibration file '" + path + "'");
  report::Json doc;
  try {
    doc = report::Json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not JSON: " + e.what());
  }
  if (doc.value("contents", "") != "calibration") throw std::runtime_error(path + ": not a calibration (contents)");
  Latencies l;
  l.get = operation_ns(doc, path, "MPI_Get 4 B");
  l.put = operation_ns(doc, path, "MPI_Put 4 B");
  l.cas = operation_ns(doc, path, "MPI_Compare_and_swap");
  l.fetch_op = operation_ns(doc, path, "MPI_Fetch_and_op");
  l.ping_pong = operation_ns(doc, path, "MPI_Send/MPI_Recv ping-pong");
  l.claim = operation_ns(doc, path, "RMA owner claim, F1 = fence only");
  l.poll = operation_ns(doc, path, "request owner poll");
  l.progress_call = operation_ns(doc, path, "owner progress call");
  l.atomic_service = std::max(l.fetch_op - l.get, 50.0);
  const std::string osc = doc.value("osc_requested", "");
  l.needs_target_progress = !doc.value("one_node", true) || (!osc.empty() && osc.find("sm") == std::string::npos);
  l.source = path + (l.needs_target_progress ? " (transport without asynchronous target progress)"
                                             : " (shared memory, osc/sm)");
  return l;
}

report::Json latencies_json(const Latencies& l) {
  return {{"source", l.source}, {"get_ns", l.get}, {"put_ns", l.put}, {"compare_and_swap_ns", l.cas},
          {"fetch_and_op_ns", l.fetch_op}, {"ping_pong_ns", l.ping_pong}, {"owner_claim_ns", l.claim},
          {"request_poll_ns", l.poll}, {"owner_progress_call_ns", l.progress_call},
          {"atomic_service_ns", l.atomic_service}, {"needs_target_progress", l.needs_target_progress},
          {"progress_every_ns", l.progress_every}};
}

}  // namespace frontsteal::mpi::sim
