// owner_path_benchmark — ns per item of the owner's claim path at 1 thread, per policy, against a plain loop.
//
// The items are trivial (the id is only kept alive), so what is measured is the protocol's own cost per item:
// O1 F1 O2 O3 O4 plus the cursor walk (and, for the batched claim, one handshake per n items). The paper's goal
// (§4.2.1, "no additional overhead for busy processors") predicts Paper and Asymmetric within about 1 ns of the plain
// loop and Fenced and SeqCst paying one full fence per item. Run with --benchmark_repetitions=N
// --benchmark_report_aggregates_only=true and read the medians; compare rows of one run only (these machines are
// noisy).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "core/frame_loop.hpp"
#include "core/membarrier.hpp"
#include "core/policies.hpp"
#include "core/std_backend.hpp"

namespace fs = frontsteal;

namespace {

constexpr fs::ItemId kItemsPerList = 1 << 16;

void report_per_item(benchmark::State& state, std::uint64_t items) {
  state.SetItemsProcessed(static_cast<std::int64_t>(items));
  state.counters["ns_per_item"] =
      benchmark::Counter(static_cast<double>(items), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Four ranges, so the cursor walk between ranges is part of what is measured.
fs::RangeList four_ranges() {
  return {{0, kItemsPerList / 4},
          {kItemsPerList / 4, kItemsPerList / 2},
          {kItemsPerList / 2, 3 * kItemsPerList / 4},
          {3 * kItemsPerList / 4, kItemsPerList}};
}

void BM_PlainLoop(benchmark::State& state) {
  std::uint64_t items = 0;
  for (auto _ : state) {
    for (fs::ItemId id = 0; id < kItemsPerList; ++id) benchmark::DoNotOptimize(id);
    items += kItemsPerList;
  }
  report_per_item(state, items);
}

template <class Policy>
void BM_OwnerPath(benchmark::State& state) {
  if constexpr (Policy::kNeedsMembarrier) {
    if (!fs::membarrier_status().available) {
      state.SkipWithError(fs::membarrier_status().detail.c_str());
      return;
    }
  }
  fs::StealingWorkers<fs::StdBackend, Policy> workers(1, kItemsPerList, 1);
  auto& owner = workers.owner(0);
  const fs::RangeList list = four_ranges();
  std::uint64_t items = 0;
  for (auto _ : state) {
    owner.install(list);
    while (const auto id = owner.try_claim()) benchmark::DoNotOptimize(*id);
    items += kItemsPerList;
  }
  report_per_item(state, items);
}

// The batched claim (Owner::try_claim_up_to): one handshake per state.range(0) items of a range.
template <class Policy>
void BM_OwnerPathBatched(benchmark::State& state) {
  fs::StealingWorkers<fs::StdBackend, Policy> workers(1, kItemsPerList, 1);
  auto& owner = workers.owner(0);
  const fs::RangeList list = four_ranges();
  const auto batch = static_cast<std::uint32_t>(state.range(0));
  std::uint64_t items = 0;
  for (auto _ : state) {
    owner.install(list);
    while (const auto ids = owner.try_claim_up_to(batch)) {
      for (fs::ItemId id = ids->begin; id < ids->end; ++id) benchmark::DoNotOptimize(id);
    }
    items += kItemsPerList;
  }
  report_per_item(state, items);
}

// The thief's side of Asymmetric: one membarrier(PRIVATE_EXPEDITED) per steal.
void BM_MembarrierHeavyFence(benchmark::State& state) {
  if (!fs::membarrier_status().available) {
    state.SkipWithError(fs::membarrier_status().detail.c_str());
    return;
  }
  for (auto _ : state) fs::membarrier_heavy_fence();
}

}  // namespace

BENCHMARK(BM_PlainLoop);
BENCHMARK_TEMPLATE(BM_OwnerPath, fs::Paper);
BENCHMARK_TEMPLATE(BM_OwnerPath, fs::Asymmetric);
BENCHMARK_TEMPLATE(BM_OwnerPath, fs::Fenced);
BENCHMARK_TEMPLATE(BM_OwnerPath, fs::Minimal);
BENCHMARK_TEMPLATE(BM_OwnerPath, fs::SeqCst);
BENCHMARK_TEMPLATE(BM_OwnerPathBatched, fs::Fenced)->Arg(1)->Arg(4)->Arg(16);
BENCHMARK(BM_MembarrierHeavyFence);

BENCHMARK_MAIN();
