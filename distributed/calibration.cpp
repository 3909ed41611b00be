// calibration.cpp — frontsteal-mpi --calibrate (calibration.hpp).
#include "distributed/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "distributed/calibration_operations.hpp"
#include "distributed/rank_watchdog.hpp"
#include "distributed/window_protocol.hpp"
#include "measure/paired_comparison.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::mpi {
namespace {

namespace ops = calibration_ops;

using Clock = std::chrono::steady_clock;
constexpr int kReps = 20000;
constexpr int kTagCalibrationDone = 184;
constexpr int kTagPing = 185;
constexpr std::size_t kBootstrapSampleCap = 500;  // an evenly strided subsample enters the bootstrap

// Times `op` kReps times or for at most op_s seconds; the watchdog names the operation if one never returns.
// `after` runs after each repetition, outside the timed region.
template <class Op, class After = void (*)()>
CalibrationRow time_op(
    std::string_view what, double op_s, Op&& op, After&& after = [] {}) {
  set_phase(what.data());  // a calibration_ops name: a NUL-terminated literal
  std::vector<double> ns;
  ns.reserve(kReps);
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(op_s));
  CalibrationRow row{std::string(what)};
  for (int i = 0; i < kReps; ++i) {
    const auto t0 = Clock::now();
    op();
    const auto t1 = Clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    after();
    note_progress();
    if (t1 > deadline) {
      row.time_bounded = true;
      break;
    }
  }
  row.repetitions = static_cast<int>(ns.size());
  std::vector<double> sub;
  for (std::size_t i = 0; i < ns.size(); i += ns.size() / kBootstrapSampleCap + 1) sub.push_back(ns[i]);
  const stats::Interval ci = stats::bootstrap_median_ci(sub);
  row.median_ns = median(ns);
  row.ci_low_ns = ci.low;
  row.ci_high_ns = ci.high;
  return row;
}

// One remote steal from rank 1's slot by core's Thief over the window, timed; after each, rank 1's End is put
// back (rank 1 never claims), so every repetition takes a share. `operations` counts what one steal issued.
CalibrationRow time_remote_steal(std::string_view what, double op_s, RmaWindow& win, WindowProtocol& thief,
                                 std::uint32_t full_end) {
  const std::uint64_t before = win.operations();
  std::uint64_t restores = 0;
  CalibrationRow row = time_op(
      what, op_s,
      [&] {
        if (thief.try_steal(1, StealHooks{}) != StealOutcome::kStolen)
          throw std::runtime_error("calibration: a remote steal from rank 1's full list took nothing");
      },
      [&] {
        win.put(1, kEnd, full_end);
        ++restores;
      });
  row.operations = static_cast<double>(win.operations() - before - restores) / row.repetitions;
  return row;
}

std::vector<CalibrationRow> measure_from_rank0(const Options& o, RmaWindow& win, WindowProtocol& thief,
                                               std::uint32_t full_end) {
  std::vector<CalibrationRow> rows;
  const double s = o.calibrate_op_s;
  rows.push_back(time_op(ops::kGet, s, [&] { (void)win.get(1, kFront); }));
  rows.push_back(time_op(ops::kPut, s, [&] { win.put(1, kEnd, full_end); }));  // the value it holds
  rows.push_back(time_op(ops::kCompareAndSwap, s, [&] { (void)win.compare_and_swap(1, kLock, 7u, 7u); }));
  rows.push_back(time_op(ops::kFetchAndOp, s, [&] { (void)win.fetch_and_op(1, kActive, 0u, MPI_SUM); }));
  {
    constexpr int kBurst = 64;
    // SUM 0: the count is left as it was.
    CalibrationRow burst =
        time_op(ops::kFetchAndOpPipelined, s, [&] { (void)win.fetch_and_op_burst(1, kActive, 0u, MPI_SUM, kBurst); });
    burst.median_ns /= kBurst;
    burst.ci_low_ns /= kBurst;
    burst.ci_high_ns /= kBurst;
    rows.push_back(burst);
  }
  rows.push_back(time_op(ops::kFlush, s, [&] { win.flush(1); }));
  rows.push_back(time_op(ops::kWinSync, s, [&] { win.sync(); }));
  // core's Owner over the window (rank 0's own slot), F1 with and without MPI_Win_sync.
  const RangeList big{{0, static_cast<ItemId>(std::min<std::uint32_t>(win.capacity(), 1u << 20))}};
  {
    const auto owner = make_window_protocol(win, 1, true, WindowPolicy::kFenced);
    owner->install(big);
    rows.push_back(time_op(ops::kClaimWithSync, s, [&] { (void)owner->try_claim(); }));
  }
  {
    const auto owner = make_window_protocol(win, 1, false, WindowPolicy::kFenced);
    owner->install(big);
    rows.push_back(time_op(ops::kClaim, s, [&] { (void)owner->try_claim(); }));
  }
  OwnerProgress poke(MPI_COMM_WORLD, 0);
  rows.push_back(time_op(ops::kProgressCall, s, [&] { poke.call(); }));
  rows.push_back(time_op(ops::kRequestPoll, s, [&] {
    int flag = 0;
    MPI_Iprobe(MPI_ANY_SOURCE, 181, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
  }));
  rows.push_back(time_op(ops::kPingPong, s, [&] {
    std::uint32_t word = 0;
    MPI_Send(&word, 1, MPI_UINT32_T, 1, kTagPing, MPI_COMM_WORLD);
    MPI_Recv(&word, 1, MPI_UINT32_T, 1, kTagPing, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }));
  rows.push_back(time_op(ops::kClockFloor, s, [] {}));
  {
    std::byte header[kHeaderBytes];
    std::vector<SegmentEntry> entries(std::min<std::uint32_t>(64, win.capacity()));
    rows.push_back(time_op(
        ops::kView, s, [&] { win.get_view(1, static_cast<std::uint32_t>(entries.size()), header, entries.data()); }));
  }
  rows.push_back(time_remote_steal(ops::kStealView, s, win, thief, full_end));
  read_victims_in_views(false);
  rows.push_back(time_remote_steal(ops::kStealWords, s, win, thief, full_end));
  read_victims_in_views(true);
  return rows;
}

}  // namespace

report::Json calibration_json(const std::vector<CalibrationRow>& rows, int ranks, const ProgressChoice& progress) {
  report::Json doc = report::document(kProgram, 1, "measured", FRONTSTEAL_GIT_COMMIT);
  doc["contents"] = "calibration";
  doc["ranks"] = ranks;
  doc["one_node"] = progress.one_node;
  doc["osc_requested"] = progress.osc_requested;
  doc["target"] = "rank 1 spinning on MPI_Iprobe (an attentive target)";
  report::Json list = report::Json::array();
  for (const CalibrationRow& r : rows) {
    list.push_back({{"operation", r.operation},
                    {"median_ns", r.median_ns},
                    {"median_ci95_ns", {r.ci_low_ns, r.ci_high_ns}},
                    {"repetitions", r.repetitions},
                    {"one_sided_operations", r.operations},
                    {"time_bounded", r.time_bounded}});
  }
  doc["operations"] = list;
  doc["published_reference_ns"] = {{"get", 1300},
                                   {"compare_and_swap", 1700},
                                   {"note", "MPI-3 RMA work stealing, two processes on one computer, async progress"}};
  return doc;
}

int calibrate(const Options& o, int rank, int ranks, RmaWindow& win, const ProgressChoice& progress) {
  if (ranks < 2) {
    if (rank == 0) std::fprintf(stderr, "%s: --calibrate needs at least 2 ranks\n", kProgram.data());
    return 2;
  }
  arm_watchdog();
  // Rank 1's list for the remote steals: one range of the window's capacity, installed by its owner.
  const auto protocol = make_window_protocol(win, ranks, false, WindowPolicy::kFenced);
  const std::uint32_t full_end = win.capacity();
  if (rank == 1) protocol->install(RangeList{{0, static_cast<ItemId>(full_end)}});
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    const std::vector<CalibrationRow> rows = measure_from_rank0(o, win, *protocol, full_end);
    for (int r = 1; r < ranks; ++r) MPI_Send(nullptr, 0, MPI_BYTE, r, kTagCalibrationDone, MPI_COMM_WORLD);
    std::printf(
        "calibration: rank 0 -> rank 1, up to %d repetitions or %.1f s each, median [95 %% CI] ns "
        "(measured, this machine; %s)\n",
        kReps, o.calibrate_op_s, progress.describe().c_str());
    for (const CalibrationRow& r : rows) {
      std::printf("  %-52s %10.0f ns  [%.0f, %.0f]  n=%d%s", r.operation.c_str(), r.median_ns, r.ci_low_ns,
                  r.ci_high_ns, r.repetitions, r.time_bounded ? " (time-bounded)" : "");
      if (r.operations > 0) std::printf("  %.1f one-sided operations each", r.operations);
      std::printf("\n");
    }
    std::printf("published reference (one computer, async progress): get ~1300 ns, CAS ~1700 ns\n");
    std::printf(
        "the remote steals' A1 lands on rank 0's own part (the active count's home): a thief on another rank pays "
        "one fetch-and-op round trip more\n");
    if (!o.json.empty()) {
      report::write_atomically(o.json, calibration_json(rows, ranks, progress).dump(2) + "\n");
      std::fprintf(stderr, "%s: wrote %s\n", kProgram.data(), o.json.c_str());
    }
  } else {
    // The target: drive the progress engine until rank 0 is done, so its operations complete (see header).
    set_phase("calibration target (progress loop)");
    while (true) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
      note_progress();
      if (!flag) continue;
      std::uint32_t word = 0;
      MPI_Recv(&word, st.MPI_TAG == kTagPing ? 1 : 0, MPI_UINT32_T, 0, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (st.MPI_TAG != kTagPing) break;                              // "done"
      MPI_Send(&word, 1, MPI_UINT32_T, 0, kTagPing, MPI_COMM_WORLD);  // the ping's echo
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return 0;
}

}  // namespace frontsteal::mpi
