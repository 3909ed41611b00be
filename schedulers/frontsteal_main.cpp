// frontsteal — the main job: load stealing per memory-order policy on a synthetic skewed workload.
//
// Each frame runs N items whose costs follow a moving "zoom": a window of N/10 items costs 40x the rest and
// slides across the ids from frame to frame, so the static block allocation is badly imbalanced and the
// previous frame's lists are a good but imperfect guess (paper §3, §4.2.1). Every item is audited: lost and
// duplicated runs are counted per policy.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/cli_args.hpp"
#include "core/execution_counter.hpp"
#include "core/membarrier.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/synthetic_work.hpp"

namespace fs = frontsteal;

namespace {

constexpr std::string_view kProgram = "frontsteal";

[[noreturn]] void usage_error(const std::string& message) { fs::cli::usage_error(kProgram, message); }

template <class T>
T parse_number(std::string_view flag, std::string_view text, T min_value, T max_value) {
  return fs::cli::parse_number<T>(kProgram, flag, text, min_value, max_value);
}

constexpr std::string_view kUsage = R"(usage: frontsteal [options]

Runs the load-stealing protocol of Kumar, Chang & Manocha (SC'96, §4.2) on persistent worker threads over
a synthetic skewed workload (a hot window of items, 40x costlier, sliding across the ids every frame), once
per memory-order policy. Prints, per policy and worker, items processed, steals and items skipped after the
re-read of Front, audits every item (lost / duplicated), and writes the results as JSON.

options:
  --policy NAME    all | SeqCst | Paper | Fenced | Minimal | Asymmetric  (default: all)
  --workers P      worker threads                                  (default: hardware threads)
  --items N        items per frame                                 (default: 5302, the paper's smallest Fig. 8 model)
  --frames F       frames per policy                               (default: 60)
  --cost-ns C      approximate cost of a cold item in nanoseconds  (default: 400)
  --seed S         victim-order seed                               (default: 1)
  --json PATH      results file                                    (default: out/frontsteal-demo.json)
  --quiet          no progress lines
  --help           this text

Policies: SeqCst, Fenced, Minimal (the weakest orders the model checker certifies) and Asymmetric are
exactly-once; Paper (no StoreLoad fence at the ListTransient
handshake) is at-least-once: an item may run twice, never zero times. Asymmetric needs Linux membarrier;
where it is unavailable the run says so and uses Fenced in its place.
)";

struct Options {
  std::string policy = "all";
  fs::WorkerId workers = std::max(1u, std::thread::hardware_concurrency());
  fs::ItemId items = 5302;
  std::uint32_t frames = 60;
  std::uint32_t cost_ns = 400;
  std::uint64_t seed = 1;
  std::string json = "out/frontsteal-demo.json";
  bool quiet = false;
};

Options parse(int argc, char** argv) {
  Options o;
  fs::cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view arg = args.flag();
    auto value = [&] { return args.value(); };
    if (arg == "--policy") {
      o.policy = value();
      if (o.policy != "all" && o.policy != "SeqCst" && o.policy != "Paper" && o.policy != "Fenced" &&
          o.policy != "Minimal" && o.policy != "Asymmetric") {
        usage_error("unknown policy '" + o.policy + "' (all, SeqCst, Paper, Fenced, Minimal, Asymmetric)");
      }
    } else if (arg == "--workers") {
      o.workers = parse_number<fs::WorkerId>(arg, value(), 1, 1024);
    } else if (arg == "--items") {
      o.items = parse_number<fs::ItemId>(arg, value(), 0, 50'000'000);
    } else if (arg == "--frames") {
      o.frames = parse_number<std::uint32_t>(arg, value(), 1, 10'000'000);
    } else if (arg == "--cost-ns") {
      o.cost_ns = parse_number<std::uint32_t>(arg, value(), 0, 10'000'000);
    } else if (arg == "--seed") {
      o.seed = parse_number<std::uint64_t>(arg, value(), 0, UINT64_MAX);
    } else if (arg == "--json") {
      o.json = value();
    } else if (arg == "--quiet") {
      o.quiet = true;
    } else {
      usage_error("unknown option '" + std::string(arg) + "'");
    }
  }
  return o;
}

std::uint32_t item_cost(fs::ItemId id, fs::ItemId n, std::uint32_t frame, std::uint32_t cold) {
  if (n == 0) return 0;
  const fs::ItemId hot_begin = static_cast<fs::ItemId>((std::uint64_t{frame} * n / 37) % n);
  return id - hot_begin < n / 10 + 1 ? cold * 40 : cold;
}

struct PolicyResult {
  std::string name;
  std::string contract;
  std::string note;  // e.g. a fallback
  std::vector<fs::WorkerFrameStats> per_worker;  // summed over frames
  std::vector<double> frame_ms;
  std::uint64_t lost = 0;
  std::uint64_t duplicated = 0;
  std::uint64_t frames_with_duplicates = 0;
  double median_ms() const {
    std::vector<double> v = frame_ms;
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  }
};

template <class Policy>
PolicyResult run_policy(const Options& o, std::string note = {}) {
  PolicyResult r;
  r.name = std::string(Policy::kName);
  r.contract = std::string(fs::name(Policy::kContract));
  r.note = std::move(note);
  fs::StealingScheduler<Policy> scheduler({.workers = o.workers, .items = o.items, .seed = o.seed});
  fs::ExecutionCounter runs(o.items);
  r.per_worker.assign(o.workers, {});
  const auto started = std::chrono::steady_clock::now();
  for (std::uint32_t f = 1; f <= o.frames; ++f) {
    const auto& st = scheduler.run_frame([&](fs::ItemId id, fs::WorkerId) {
      runs.record(id);
      fs::spin_work(item_cost(id, o.items, f, o.cost_ns));
    });
    const fs::ExecutionAudit audit = runs.audit_and_reset();
    r.lost += audit.lost;
    r.duplicated += audit.duplicated;
    if (audit.duplicated > 0) ++r.frames_with_duplicates;
    for (fs::WorkerId w = 0; w < o.workers; ++w) r.per_worker[w] += st.workers[w];
    r.frame_ms.push_back(st.wall_ns / 1e6);
    const double since_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!o.quiet && (f == o.frames || f % 20 == 0)) {
      std::fprintf(stderr, "  %-10s frame %u/%u  (%.1f s)\n", r.name.c_str(), f, o.frames, since_s);
    }
  }
  return r;
}

void print_result(const PolicyResult& r, const Options& o) {
  std::int64_t busy = 0;
  for (const auto& w : r.per_worker) busy += w.busy_ns;
  double wall_ns = 0;
  for (double ms : r.frame_ms) wall_ns += ms * 1e6;
  std::printf("\n== %s (%s)%s%s\n", r.name.c_str(), r.contract.c_str(), r.note.empty() ? "" : ": ", r.note.c_str());
  std::printf("median frame %.3f ms   utilization %.1f%%   lost %llu   duplicated %llu (in %llu of %u frames)\n",
              r.median_ms(), wall_ns > 0 ? 100.0 * busy / (wall_ns * o.workers) : 0.0,
              static_cast<unsigned long long>(r.lost), static_cast<unsigned long long>(r.duplicated),
              static_cast<unsigned long long>(r.frames_with_duplicates), o.frames);
  std::printf("%6s %12s %10s %10s %12s %12s %8s\n", "worker", "items", "steals", "attempts", "items stolen",
              "items skipped", "busy");
  for (std::size_t w = 0; w < r.per_worker.size(); ++w) {
    const auto& s = r.per_worker[w];
    std::printf("%6zu %12llu %10llu %10llu %12llu %12llu %7.1f%%\n", w,
                static_cast<unsigned long long>(s.items_processed), static_cast<unsigned long long>(s.steals_succeeded),
                static_cast<unsigned long long>(s.steal_attempts), static_cast<unsigned long long>(s.items_stolen),
                static_cast<unsigned long long>(s.items_skipped), wall_ns > 0 ? 100.0 * s.busy_ns / wall_ns : 0.0);
  }
}

void write_json(const std::vector<PolicyResult>& results, const Options& o) {
  const std::filesystem::path path(o.json);
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) {
      std::cerr << "frontsteal: cannot create " << path.parent_path() << ": " << ec.message() << "\n";
      std::exit(1);
    }
  }
  std::ofstream out(path);
  if (!out) {
    std::cerr << "frontsteal: cannot write " << path << ": " << std::strerror(errno) << "\n";
    std::exit(1);
  }
  out << "{\n  \"kind\": \"measured\",\n  \"workload\": \"synthetic skewed (sliding hot window, 40x)\",\n"
      << "  \"workers\": " << o.workers << ", \"items\": " << o.items << ", \"frames\": " << o.frames
      << ", \"cost_ns\": " << o.cost_ns << ", \"seed\": " << o.seed
      << ", \"hardware_threads\": " << std::thread::hardware_concurrency() << ",\n  \"policies\": [\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const auto& r = results[i];
    out << "    {\"policy\": \"" << r.name << "\", \"contract\": \"" << r.contract << "\", \"note\": \"" << r.note
        << "\", \"median_frame_ms\": " << r.median_ms() << ", \"lost\": " << r.lost
        << ", \"duplicated\": " << r.duplicated << ", \"frames_with_duplicates\": " << r.frames_with_duplicates
        << ",\n     \"workers\": [";
    for (std::size_t w = 0; w < r.per_worker.size(); ++w) {
      const auto& s = r.per_worker[w];
      out << (w ? ", " : "") << "{\"items\": " << s.items_processed << ", \"steals\": " << s.steals_succeeded
          << ", \"steal_attempts\": " << s.steal_attempts << ", \"items_stolen\": " << s.items_stolen
          << ", \"items_skipped\": " << s.items_skipped << ", \"busy_ns\": " << s.busy_ns
          << ", \"idle_ns\": " << s.idle_ns << "}";
    }
    out << "],\n     \"frame_ms\": [";
    for (std::size_t f = 0; f < r.frame_ms.size(); ++f) out << (f ? ", " : "") << r.frame_ms[f];
    out << "]}" << (i + 1 < results.size() ? "," : "") << "\n";
  }
  out << "  ]\n}\n";
  std::printf("\nresults written to %s\n", o.json.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::printf("frontsteal: load stealing, %u workers (%u hardware threads), %u items, %u frames per policy\n",
              o.workers, std::thread::hardware_concurrency(), o.items, o.frames);
  std::vector<PolicyResult> results;
  auto wanted = [&](std::string_view name) { return o.policy == "all" || o.policy == name; };
  try {
    if (wanted("SeqCst")) results.push_back(run_policy<fs::SeqCst>(o));
    if (wanted("Paper")) results.push_back(run_policy<fs::Paper>(o));
    if (wanted("Fenced")) results.push_back(run_policy<fs::Fenced>(o));
    if (wanted("Minimal")) results.push_back(run_policy<fs::Minimal>(o));
    if (wanted("Asymmetric")) {
      if (fs::membarrier_status().available) {
        results.push_back(run_policy<fs::Asymmetric>(o));
      } else {
        const std::string note = "Asymmetric unavailable (" + fs::membarrier_status().detail + "): ran Fenced instead";
        std::fprintf(stderr, "frontsteal: %s\n", note.c_str());
        results.push_back(run_policy<fs::Fenced>(o, note));
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "frontsteal: " << e.what() << "\n";
    return 1;
  }
  bool contract_broken = false;
  for (const auto& r : results) {
    print_result(r, o);
    if (r.lost > 0 || (r.contract == "exactly-once" && r.duplicated > 0)) contract_broken = true;
  }
  write_json(results, o);
  if (contract_broken) {
    std::fprintf(stderr, "frontsteal: a policy broke its contract (see lost/duplicated above)\n");
    return 3;
  }
  return 0;
}
