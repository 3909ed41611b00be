// distributed/calibration.hpp and the simulator's reader of it (rma_simulator.hpp, latencies_from_calibration):
// what frontsteal-mpi --calibrate --json writes, the distributed simulator reads back, operation by operation.
// No MPI run: the rows are made here, with values known in advance.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "distributed/calibration.hpp"
#include "distributed/calibration_operations.hpp"
#include "distributed/rma_simulator.hpp"

namespace mpi = frontsteal::mpi;
namespace ops = frontsteal::mpi::calibration_ops;
namespace sim = frontsteal::mpi::sim;
namespace fs = std::filesystem;

namespace {

// Every operation --calibrate times, each with a distinct median so a swapped lookup shows.
std::vector<mpi::CalibrationRow> every_operation() {
  std::vector<mpi::CalibrationRow> rows;
  double ns = 100;
  for (std::string_view name :
       {ops::kGet, ops::kPut, ops::kCompareAndSwap, ops::kFetchAndOp, ops::kFlush, ops::kWinSync, ops::kClaimWithSync,
        ops::kClaim, ops::kProgressCall, ops::kRequestPoll, ops::kPingPong, ops::kClockFloor}) {
    rows.push_back({std::string(name), ns, ns - 1, ns + 1, 1000, false});
    ns += 100;
  }
  return rows;
}

class TempFile {
 public:
  explicit TempFile(const std::string& text)
      : path_(fs::temp_directory_path() /
              ("frontsteal-calibration-" + std::to_string(::getpid()) + "-" + std::to_string(counter_++) + ".json")) {
    std::ofstream(path_) << text;
  }
  ~TempFile() { fs::remove(path_); }
  std::string path() const { return path_.string(); }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

mpi::ProgressChoice shared_memory() {
  mpi::ProgressChoice p;
  p.one_node = true;
  p.open_mpi = true;
  return p;
}

}  // namespace

TEST_CASE("the simulator reads back every latency the calibration writes", "[distributed][calibration]") {
  const TempFile file(mpi::calibration_json(every_operation(), 2, shared_memory()).dump(2));
  const sim::Latencies l = sim::latencies_from_calibration(file.path());
  CHECK(l.get == 100);
  CHECK(l.put == 200);
  CHECK(l.cas == 300);
  CHECK(l.fetch_op == 400);
  CHECK(l.claim == 800);  // the default owner (F1 = fence only), not the MPI_Win_sync one (700)
  CHECK(l.progress_call == 900);
  CHECK(l.poll == 1000);
  CHECK(l.ping_pong == 1100);
  CHECK(l.atomic_service == 300);  // fetch-and-op beyond a get
  CHECK_FALSE(l.needs_target_progress);
  CHECK(l.source.find("osc/sm") != std::string::npos);
}

TEST_CASE("a transport that needs the target's progress is recognised from the calibration",
          "[distributed][calibration]") {
  mpi::ProgressChoice tcp = shared_memory();
  tcp.one_node = false;
  const TempFile across_nodes(mpi::calibration_json(every_operation(), 2, tcp).dump());
  CHECK(sim::latencies_from_calibration(across_nodes.path()).needs_target_progress);

  mpi::ProgressChoice pt2pt = shared_memory();
  pt2pt.osc_requested = "pt2pt";
  const TempFile forced(mpi::calibration_json(every_operation(), 2, pt2pt).dump());
  CHECK(sim::latencies_from_calibration(forced.path()).needs_target_progress);

  mpi::ProgressChoice sm = shared_memory();
  sm.osc_requested = "sm";
  const TempFile asked_sm(mpi::calibration_json(every_operation(), 2, sm).dump());
  CHECK_FALSE(sim::latencies_from_calibration(asked_sm.path()).needs_target_progress);
}

TEST_CASE("an atomic costs at least 50 ns of its home rank's time", "[distributed][calibration]") {
  std::vector<mpi::CalibrationRow> rows = every_operation();
  for (auto& r : rows) {
    if (r.operation == ops::kFetchAndOp) r.median_ns = 110;  // 10 ns beyond a get
  }
  const TempFile file(mpi::calibration_json(rows, 2, shared_memory()).dump());
  CHECK(sim::latencies_from_calibration(file.path()).atomic_service == 50);
}

TEST_CASE("over a transport that needs the target's progress an atomic holds its home for the pipelined time",
          "[distributed][calibration]") {
  std::vector<mpi::CalibrationRow> rows = every_operation();
  rows.push_back({std::string(ops::kFetchAndOpPipelined), 9000, 8900, 9100, 1000, false});
  mpi::ProgressChoice tcp = shared_memory();
  tcp.one_node = false;
  const TempFile across_nodes(mpi::calibration_json(rows, 2, tcp).dump());
  CHECK(sim::latencies_from_calibration(across_nodes.path()).atomic_service == 9000);
  // On shared memory the origin applies the atomic itself: the difference to a get, as without the row.
  const TempFile one_node(mpi::calibration_json(rows, 2, shared_memory()).dump());
  CHECK(sim::latencies_from_calibration(one_node.path()).atomic_service == 300);
  // A calibration written before the pipelined row: the difference, over TCP too.
  const TempFile older(mpi::calibration_json(every_operation(), 2, tcp).dump());
  CHECK(sim::latencies_from_calibration(older.path()).atomic_service == 300);
}

TEST_CASE("a calibration without an operation the simulator needs is refused, naming it",
          "[distributed][calibration]") {
  std::vector<mpi::CalibrationRow> rows = every_operation();
  std::erase_if(rows, [](const mpi::CalibrationRow& r) { return r.operation == ops::kPingPong; });
  const TempFile file(mpi::calibration_json(rows, 2, shared_memory()).dump());
  CHECK_THROWS_WITH(sim::latencies_from_calibration(file.path()),
                    Catch::Contains("no operation 'MPI_Send/MPI_Recv ping-pong 4 B (round trip)'"));
}

TEST_CASE("a file that is no calibration is refused with its name", "[distributed][calibration]") {
  const TempFile not_json("calibration: get 100 ns\n");
  CHECK_THROWS_WITH(sim::latencies_from_calibration(not_json.path()), Catch::Contains(not_json.path() + ": not JSON"));
  const TempFile other(R"({"contents": "frames", "operations": []})");
  CHECK_THROWS_WITH(sim::latencies_from_calibration(other.path()), Catch::Contains("not a calibration"));
  CHECK_THROWS_WITH(sim::latencies_from_calibration("/nonexistent/calibration.json"),
                    Catch::Contains("cannot read calibration file '/nonexistent/calibration.json'"));
}

TEST_CASE("the calibration document says what it is and keeps each interval", "[distributed][calibration]") {
  const frontsteal::report::Json doc = mpi::calibration_json(every_operation(), 3, shared_memory());
  CHECK(doc.at("contents") == "calibration");
  CHECK(doc.at("kind") == "measured");
  CHECK(doc.at("ranks") == 3);
  REQUIRE(doc.at("operations").size() == 12);
  const auto& first = doc.at("operations").at(0);
  CHECK(first.at("operation") == std::string(ops::kGet));
  CHECK(first.at("median_ci95_ns").at(0) == 99.0);
  CHECK(first.at("median_ci95_ns").at(1) == 101.0);
  CHECK(first.at("repetitions") == 1000);
}

TEST_CASE("the progress choice is described in words", "[distributed][owner_progress]") {
  mpi::ProgressChoice p = shared_memory();
  CHECK(p.describe().find("off") != std::string::npos);
  CHECK(p.describe().find("share one node") != std::string::npos);
  p.every_us = 0;
  CHECK(p.describe().find("after every item") != std::string::npos);
  p.every_us = 50;
  p.one_node = false;
  p.osc_requested = "pt2pt";
  CHECK(p.describe().find("at most every 50 us") != std::string::npos);
  CHECK(p.describe().find("span several nodes") != std::string::npos);
  CHECK(p.describe().find("requested: pt2pt") != std::string::npos);
  p.open_mpi = false;
  CHECK(p.describe().find("not Open MPI") != std::string::npos);
}
