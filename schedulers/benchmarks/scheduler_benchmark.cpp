// scheduler_benchmark — Google Benchmark for every scheduler of schedulers/registry.hpp.
//
//   owner_overhead/<scheduler>[/grain1]   P = 1, 100,000 trivial items per frame, claim timing off: the cost
//                                         a scheduler adds per item (counter ns/item) when nobody steals.
//                                         grain1: the chunked schedulers claiming one item at a time.
//   deque/push_take                       one Chase–Lev push + take on the owner's end (the raw "take").
//   skewed/<scheduler>/P                  4,096 items of ~0.2-3 µs with a hot window (1/8 of the items,
//                                         20x) that moves every frame; time per frame, real time.
// Ratios are meant to be read within one run (the machines are noisy): see docs/benchmark.md, "Benchmarks".
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/synthetic_work.hpp"
#include "schedulers/chase_lev_deque.hpp"
#include "schedulers/registry.hpp"

namespace fs = frontsteal;
namespace sc = frontsteal::sched;

namespace {

constexpr fs::ItemId kOverheadItems = 100000;

void owner_overhead(benchmark::State& state, const sc::SchedulerInfo* info, fs::ItemId grain) {
  auto s = info->make({.workers = 1, .items = kOverheadItems, .grain = grain, .seed = 1, .time_claims = false}, {});
  auto item = [](fs::ItemId id, fs::WorkerId) { benchmark::DoNotOptimize(id); };
  for (auto _ : state) s->run_frame(item);
  state.counters["ns/item"] = benchmark::Counter(static_cast<double>(state.iterations()) * kOverheadItems,
                                                 benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void serial_loop(benchmark::State& state) {
  auto item = [](fs::ItemId id, fs::WorkerId) { benchmark::DoNotOptimize(id); };
  const sc::ItemFunctionRef ref(item);
  const sc::ItemFunctionRef* volatile opaque = &ref;  // the call stays indirect, as in every scheduler
  for (auto _ : state) {
    for (fs::ItemId id = 0; id < kOverheadItems; ++id) (*opaque)(id, 0);
  }
  state.counters["ns/item"] = benchmark::Counter(static_cast<double>(state.iterations()) * kOverheadItems,
                                                 benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void deque_push_take(benchmark::State& state) {
  sc::ChaseLevDeque<std::uint64_t> d(64);
  std::uint64_t x = 0, sink = 0;
  for (auto _ : state) {
    d.push(x++);
    d.take(x);
    sink += x;
  }
  benchmark::DoNotOptimize(sink);
}

void skewed(benchmark::State& state, const sc::SchedulerInfo* info) {
  constexpr fs::ItemId n = 4096;
  const auto p = static_cast<fs::WorkerId>(state.range(0));
  auto s = info->make({.workers = p, .items = n, .seed = 1}, {});
  std::vector<std::uint32_t> cost(n);
  std::mt19937_64 rng(42);
  double utilization = 0;
  std::uint64_t frames = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const fs::ItemId hot = static_cast<fs::ItemId>(rng() % n);
    for (fs::ItemId i = 0; i < n; ++i) {
      const bool is_hot = (i + n - hot) % n < n / 8;
      cost[i] = static_cast<std::uint32_t>((1 + rng() % 8) * (is_hot ? 20 : 1) * 16);
    }
    state.ResumeTiming();
    auto item = [&cost](fs::ItemId id, fs::WorkerId) { fs::spin_work(cost[id]); };
    utilization += s->run_frame(item).utilization();
    ++frames;
  }
  state.counters["utilization"] = frames ? utilization / frames : 0;
}

void register_all() {
  benchmark::RegisterBenchmark("owner_overhead/serial-loop", serial_loop)->UseRealTime();
  for (const auto& info : sc::scheduler_registry()) {
    benchmark::RegisterBenchmark(("owner_overhead/" + info.name).c_str(), owner_overhead, &info, fs::ItemId{0})
        ->UseRealTime();
    if (info.name == "queue-mutex" || info.name == "counter-atomic" || info.name == "tbb-affinity") {
      benchmark::RegisterBenchmark(("owner_overhead/" + info.name + "/grain1").c_str(), owner_overhead, &info,
                                   fs::ItemId{1})
          ->UseRealTime();
    }
  }
  benchmark::RegisterBenchmark("deque/push_take", deque_push_take);
  const long cores = std::max(1u, std::thread::hardware_concurrency());
  for (const auto& info : sc::scheduler_registry()) {
    if (info.contract != fs::Contract::kExactlyOnce) continue;
    auto* b = benchmark::RegisterBenchmark(("skewed/" + info.name).c_str(), skewed, &info);
    for (long p = 1; p <= cores; p *= 2) b->Arg(p);
    if ((cores & (cores - 1)) != 0) b->Arg(cores);
    b->UseRealTime()->Unit(benchmark::kMillisecond);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
