// own_item_function — a user's own workload on frontsteal: the rows of a Mandelbrot image. A row's cost is
// the number of iterations its points take to escape, so rows through the set cost up to max-iter per point
// and rows far from it a few: a skewed workload whose costs nobody knows in advance, which is what load
// stealing is for.
//
// 1. StealingScheduler<Fenced> (frontsteal::core, header-only) runs one frame directly: every row exactly once.
// 2. The same item function through the scheduler interface (frontsteal::schedulers, registry.hpp):
//    "stealing/Fenced" (the same StealingScheduler behind the interface) against "queue-mutex" (the paper's
//    global queue), frame after frame, the two interleaved so drift of a shared machine hits both alike.
//    Frame times: medians with 95 % bootstrap intervals, and the paired ratio (measure/paired_comparison.hpp);
//    the noise monitor says whether other processes shared the machine meanwhile.
// Every frame is checked: each row ran exactly once, and the image's checksum equals the serial one.
// Exit 0 when every check held, 1 when one failed, 2 on a usage error.
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "core/stealing_scheduler.hpp"
#include "measure/noise_monitor.hpp"
#include "measure/paired_comparison.hpp"
#include "reporting/command_line.hpp"
#include "schedulers/registry.hpp"

namespace {

constexpr const char* kProgram = "own_item_function";

struct Options {
  frontsteal::WorkerId threads = 2;
  frontsteal::ItemId rows = 256;
  std::uint32_t width = 256;
  std::uint32_t max_iter = 1000;
  std::uint32_t frames = 15;
  std::string out;
};

// The options through frontsteal::reporting's CommandLine (CLI11), as every frontsteal program reads them:
// defaults shown in --help, a mistake exits 2 naming the flag.
Options parse(int argc, char** argv) {
  Options o;
  frontsteal::report::CommandLine cli(kProgram,
                                      "Mandelbrot rows as frontsteal items: stealing/Fenced against queue-mutex.",
                                      "Exit status: 0 when every check held, 1 when one failed, 2 on a usage error.");
  cli.option("--threads", o.threads, "workers")->type_name("P")->check(CLI::Range(1u, 256u));
  cli.option("--rows", o.rows, "items = image rows")->type_name("N")->check(CLI::Range(1u, 1u << 20));
  cli.option("--width", o.width, "points per row")->type_name("W")->check(CLI::Range(1u, 1u << 16));
  cli.option("--max-iter", o.max_iter, "iteration bound per point")->type_name("K")->check(CLI::Range(1u, 1u << 20));
  cli.option("--frames", o.frames, "measured frames per scheduler, after one warm-up frame")
      ->type_name("F")
      ->check(CLI::Range(3u, 100000u));
  cli.option("--out", o.out, "also write every frame as CSV (scheduler,frame,wall_ns,steals)")->type_name("FILE");
  cli.parse(argc, argv);
  return o;
}

// The workload: row y of the image of [-2, 0.6] x [-1.2, 1.2]; its result is the sum of its escape counts.
struct Mandelbrot {
  Options o;
  std::vector<std::uint64_t> row_sum;
  std::vector<std::atomic<std::uint32_t>> runs;  // per row, calls this frame: the exactly-once check

  explicit Mandelbrot(const Options& opt) : o(opt), row_sum(opt.rows), runs(opt.rows) {}

  std::uint64_t row(frontsteal::ItemId y) const {
    std::uint64_t sum = 0;
    const double ci = -1.2 + 2.4 * (y + 0.5) / o.rows;
    for (std::uint32_t x = 0; x < o.width; ++x) {
      const double cr = -2.0 + 2.6 * (x + 0.5) / o.width;
      double zr = 0, zi = 0;
      std::uint32_t k = 0;
      while (k < o.max_iter && zr * zr + zi * zi <= 4.0) {
        const double t = zr * zr - zi * zi + cr;
        zi = 2 * zr * zi + ci;
        zr = t;
        ++k;
      }
      sum += k;
    }
    return sum;
  }
  // The item function: (item, worker) -> effects. Each row writes only its own slot.
  void operator()(frontsteal::ItemId y, frontsteal::WorkerId) {
    row_sum[y] = row(y);
    runs[y].fetch_add(1, std::memory_order_relaxed);
  }
  // After a frame: every row ran once and the image is the serial one. Re-arms the counts.
  bool check_frame(std::uint64_t expected_sum, const std::string& who) {
    std::uint64_t sum = 0;
    bool ok = true;
    for (frontsteal::ItemId y = 0; y < o.rows; ++y) {
      const std::uint32_t n = runs[y].exchange(0, std::memory_order_relaxed);
      if (n != 1) {
        std::cerr << who << ": row " << y << " ran " << n << " times\n";
        ok = false;
      }
      sum += row_sum[y];
    }
    if (sum != expected_sum) {
      std::cerr << who << ": checksum " << sum << " != serial " << expected_sum << "\n";
      ok = false;
    }
    return ok;
  }
};

void print_interval(const char* name, const std::vector<double>& ms) {
  const auto ci = frontsteal::stats::bootstrap_median_ci(ms);
  std::printf("  %-16s median %8.3f ms  95%% CI [%.3f, %.3f]  (%zu frames)\n", name, ci.median, ci.low, ci.high,
              ms.size());
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  Mandelbrot work(o);
  std::uint64_t serial = 0;
  for (frontsteal::ItemId y = 0; y < o.rows; ++y) serial += work.row(y);
  bool ok = true;

  // 1. The protocol itself, header-only: any callable (ItemId, WorkerId) is an item function.
  {
    frontsteal::StealingScheduler<frontsteal::Fenced> direct({.workers = o.threads, .items = o.rows, .seed = 1});
    const frontsteal::FrameStats& st = direct.run_frame(work);
    ok &= work.check_frame(serial, "StealingScheduler<Fenced>");
    std::uint64_t steals = 0;
    for (const auto& w : st.workers) steals += w.steals_succeeded;
    std::printf("StealingScheduler<Fenced>: %u rows on %u workers, %.3f ms, %llu steals, exactly once: %s\n", o.rows,
                o.threads, st.wall_ns / 1e6, static_cast<unsigned long long>(steals), ok ? "yes" : "NO");
  }

  // 2. Through the scheduler interface: any registry entry runs the same item function.
  namespace sched = frontsteal::sched;
  const std::vector<std::string> names{"stealing/Fenced", "queue-mutex"};
  std::vector<std::unique_ptr<sched::Scheduler>> schedulers;
  for (const auto& n : names) {
    const sched::SchedulerInfo* info = sched::find_scheduler(n);
    if (info == nullptr) {
      std::cerr << kProgram << ": no scheduler " << n << " in this frontsteal\n";
      return 1;
    }
    schedulers.push_back(info->make({.workers = o.threads, .items = o.rows, .seed = 1}, sched::WorkloadHints{}));
  }
  std::vector<std::vector<double>> ms(names.size());
  std::ofstream csv;
  if (!o.out.empty()) {
    csv.open(o.out);
    if (!csv) {
      std::cerr << kProgram << ": --out: cannot write " << o.out << "\n";
      return 2;
    }
    csv << "scheduler,frame,wall_ns,steals\n";
  }
  const frontsteal::noise::ProcSample before = frontsteal::noise::sample_now();
  for (std::uint32_t f = 0; f <= o.frames; ++f) {  // frame 0: warm-up (threads, caches, stealing's lists)
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::size_t s = (f % 2 == 0) ? i : names.size() - 1 - i;  // alternate who goes first
      const frontsteal::FrameStats& st = schedulers[s]->run_frame(work);
      ok &= work.check_frame(serial, names[s]);
      std::uint64_t steals = 0;
      for (const auto& w : st.workers) steals += w.steals_succeeded;
      if (csv) csv << names[s] << ',' << f << ',' << st.wall_ns << ',' << steals << '\n';
      if (f > 0) ms[s].push_back(st.wall_ns / 1e6);
    }
  }
  const auto noise = frontsteal::noise::assess(
      frontsteal::noise::usage_between(before, frontsteal::noise::sample_now()), frontsteal::noise::Thresholds{});

  std::printf("measured, %u frames each after one warm-up, %u workers, frame wall time:\n", o.frames, o.threads);
  for (std::size_t s = 0; s < names.size(); ++s) print_interval(names[s].c_str(), ms[s]);
  const auto cmp = frontsteal::stats::compare_paired(ms[0], ms[1]);
  std::printf("  stealing/Fenced / queue-mutex: ratio %.3f, 95%% CI [%.3f, %.3f]: %s (%+.1f %%)\n", cmp.ratio.median,
              cmp.ratio.low, cmp.ratio.high, frontsteal::stats::to_string(cmp.verdict), cmp.effect_pct);
  std::printf("machine: %s\n", noise.busy ? ("BUSY, " + noise.reason).c_str() : "quiet");
  std::printf("exactly-once and checksum, every frame of every scheduler: %s\n", ok ? "pass" : "FAIL");
  return ok ? 0 : 1;
}
