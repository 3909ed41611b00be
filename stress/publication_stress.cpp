// frontsteal-stress-publication — greedy rendering's publication and reclamation (core/component_publication.hpp)
// on real threads, with chaos injected at its labelled sites: a pusher thread drawing every component as fast as
// it can, P tessellators (the stealing scheduler) writing every surface every frame, the caller as frame driver.
//
// What is checked, per pusher update and component:
//   torn        the surfaces of the slot it read carry different frames (invariant I1);
//   reuse       a tessellator was writing the slot while the pusher read it: each slot counts its writers in
//               flight, and the pusher reads every surface's stamp twice around its "draw" (invariant I2);
//   backwards   a component showed an older frame than in an earlier update (I3);
// plus, under ThreadSanitizer, races on the triangle cells themselves (the sound policy's cells are plain memory;
// the planted defects' cells are relaxed atomics so that the audit, not TSan's halt, reports them).
// Outcome histogram: how many frames behind the newest finished frame each drawn component was (the lag).
// Negative controls: Broken:ReuseWithoutGrace and Broken:PublishEachSurface must be caught; the run fails if not.
// Each runs until its first catch (up to --control-seconds), not for --seconds: how soon a pusher update overlaps a
// premature reuse depends on how the machine's load schedules the threads, so a fixed duration can miss it.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/component_publication.hpp"
#include "core/policies.hpp"
#include "core/publication_policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/watchdog.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "stress/chaos_backend.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif

using namespace frontsteal;
using namespace frontsteal::stress;
namespace report = frontsteal::report;

namespace {

constexpr const char* kProgram = "frontsteal-stress-publication";
constexpr const char* kDescription = R"(Stress test of greedy rendering's triangle publication and buffer reclamation on real threads with chaos: a
pusher that never waits, P tessellators (the stealing scheduler, Fenced), the caller as frame driver. Audits every
pusher update for torn components, use of a slot after its reuse and components going back in time; the planted
defects Broken:ReuseWithoutGrace and Broken:PublishEachSurface must be caught. Build with the tsan preset for
ThreadSanitizer's verdict on the triangle cells as well. Exits 1 on any unexpected outcome, 2 for bad usage.)";

struct Options {
  double seconds = 2;
  double control_seconds = 60;
  std::vector<WorkerId> threads{2, 4};
  std::vector<SlotIndex> slots{2, 3};
  std::uint32_t components = 24;
  std::uint32_t chaos = 20000;
  std::uint64_t seed = 1;
  std::string out = "out/stress-publication";
  bool quiet = false;
};

struct CaseResult {
  std::string policy;
  WorkerId threads = 0;
  SlotIndex slots = 0;
  bool negative_control = false;
  std::uint64_t frames = 0, updates = 0, driver_waits = 0;
  std::uint64_t torn = 0, reuse = 0, backwards = 0;
  double seconds = 0;  // for a negative control: until the first catch
  std::map<std::uint64_t, std::uint64_t> lag;  // frames behind the newest finished frame -> component draws
  bool passed() const { return negative_control ? (torn + reuse + backwards) > 0 : (torn + reuse + backwards) == 0; }
};

// One triangle cell per (component, slot, surface): the frame that wrote it. Plain memory for the sound policy
// (ThreadSanitizer checks it), relaxed atomics for the planted defects (the audit reports them, TSan does not halt).
template <bool kPlain>
struct TriangleCell {
  std::uint64_t frame = 0;
  std::uint64_t read() const { return frame; }
  void write(std::uint64_t f) { frame = f; }
};
template <>
struct TriangleCell<false> {
  std::atomic<std::uint64_t> frame{0};
  std::uint64_t read() const { return frame.load(std::memory_order::relaxed); }
  void write(std::uint64_t f) { frame.store(f, std::memory_order::relaxed); }
};

template <class Policy>
CaseResult run_case(const Options& o, WorkerId threads, SlotIndex slots, bool negative_control) {
  constexpr bool kPlain = !has(Policy::defects(), Defect::kReuseWithoutGrace) && !has(Policy::defects(), Defect::kPublishEachSurface);
  CaseResult r;
  r.policy = std::string(Policy::kName);
  r.threads = threads;
  r.slots = slots;
  r.negative_control = negative_control;
  std::mt19937_64 rng(o.seed);
  std::vector<std::uint32_t> sizes(o.components);
  std::vector<ComponentId> owner;       // surface -> component
  std::vector<std::uint32_t> position;  // surface -> index inside its component
  for (ComponentId c = 0; c < o.components; ++c) {
    sizes[c] = 1 + static_cast<std::uint32_t>(rng() % 4);
    for (std::uint32_t i = 0; i < sizes[c]; ++i) {
      owner.push_back(c);
      position.push_back(i);
    }
  }
  const auto surfaces = static_cast<ItemId>(owner.size());
  ComponentPublication<ChaosBackend, Policy> publication(sizes, slots);
  std::vector<TriangleCell<kPlain>> cells(static_cast<std::size_t>(o.components) * slots * 4);
  std::vector<std::atomic<std::uint32_t>> writing(static_cast<std::size_t>(o.components) * slots);
  const auto cell = [&](ComponentId c, SlotIndex s, std::uint32_t i) -> TriangleCell<kPlain>& {
    return cells[(static_cast<std::size_t>(c) * slots + s) * 4 + i];
  };
  std::atomic<std::uint64_t> newest_frame{0};
  std::atomic<bool> stop{false};
  std::atomic<bool> caught{false};  // the pusher saw a violation: a negative control can end its case
  chaos_settings() = {o.chaos, o.seed};  // before any thread of the case starts; reset after all have joined

  // The pusher reads every component's slot first and checks it again after "drawing" them all, so it holds
  // each slot for a whole update, as the renderer does.
  std::thread pusher([&] {
    std::vector<std::uint64_t> last(o.components, 0), first(o.components, 0);
    std::vector<SlotIndex> held(o.components);
    std::vector<char> torn(o.components);
    while (!stop.load(std::memory_order::relaxed)) {
      publication.begin_update();
      const std::uint64_t newest = newest_frame.load(std::memory_order::relaxed);
      for (ComponentId c = 0; c < o.components; ++c) {
        held[c] = publication.read(c);
        if (held[c] == decltype(publication)::kNothing) continue;
        first[c] = cell(c, held[c], 0).read();
        torn[c] = false;
        for (std::uint32_t i = 1; i < sizes[c]; ++i) torn[c] = torn[c] || cell(c, held[c], i).read() != first[c];
        r.reuse += writing[static_cast<std::size_t>(c) * slots + held[c]].load(std::memory_order::relaxed) != 0;
      }
      // "Drawing": the window a premature reuse would hit. A sleep, not a yield, so that tessellators get a core
      // even when other processes load every core (a yield alone left the defect uncaught under CI load).
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      for (ComponentId c = 0; c < o.components; ++c) {
        if (held[c] == decltype(publication)::kNothing) continue;
        bool reused = writing[static_cast<std::size_t>(c) * slots + held[c]].load(std::memory_order::relaxed) != 0;
        for (std::uint32_t i = 0; i < sizes[c]; ++i) reused = reused || (!torn[c] && cell(c, held[c], i).read() != first[c]);
        r.torn += torn[c];
        r.reuse += reused;
        r.backwards += first[c] < last[c];
        last[c] = std::max(last[c], first[c]);
        ++r.lag[newest >= first[c] ? newest - first[c] : 0];
      }
      publication.end_update();
      ++r.updates;
      if (r.torn + r.reuse + r.backwards > 0) caught.store(true, std::memory_order::relaxed);
    }
  });

  {
    StealingScheduler<Fenced, ChaosBackend> scheduler({.workers = threads, .items = surfaces, .seed = o.seed});
    // A frame that stops moving ends the run with every worker's state (core/watchdog.hpp), not a ctest timeout.
    const Watchdog dog = watch_workers(scheduler, "frontsteal-stress-publication: " + r.policy + ", P=" +
                                                      std::to_string(threads) + ", slots=" + std::to_string(slots));
    const auto start = std::chrono::steady_clock::now();
    const auto deadline = start + std::chrono::duration<double>(negative_control ? o.control_seconds : o.seconds);
    while (std::chrono::steady_clock::now() < deadline &&
           !(negative_control && caught.load(std::memory_order::relaxed))) {
      r.driver_waits += publication.prepare_frame();
      const std::uint64_t frame = ++r.frames;
      scheduler.run_frame([&](ItemId id, WorkerId) {
        const ComponentId c = owner[id];
        const SlotIndex s = publication.back_slot(c);
        std::atomic<std::uint32_t>& w = writing[static_cast<std::size_t>(c) * slots + s];
        w.fetch_add(1, std::memory_order::relaxed);
        cell(c, s, position[id]).write(frame);
        w.fetch_sub(1, std::memory_order::release);
        publication.finish_surface(c);
      });
      newest_frame.store(frame, std::memory_order::relaxed);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  stop.store(true, std::memory_order::relaxed);
  pusher.join();
  chaos_settings() = {0, o.seed};
  return r;
}

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription);
  cli.option("--seconds", o.seconds, "run time per case of the sound policy (per P x slots)")->check(CLI::Range(0.01, 3600.0));
  cli.option("--control-seconds", o.control_seconds, "a negative control runs until its defect is caught; it fails "
             "only if this many seconds pass first")->check(CLI::Range(0.01, 3600.0));
  cli.app().add_option("--threads", o.threads, "tessellator counts, comma-separated")->delimiter(',')->check(CLI::Range(1u, 256u));
  cli.app().add_option("--slots", o.slots, "slots per component, comma-separated")->delimiter(',')->check(CLI::Range(2, 16));
  cli.option("--components", o.components, "components (1..4 surfaces each, seeded)")->check(CLI::Range(1u, 100000u));
  cli.option("--chaos", o.chaos, "chaos injections per million labelled accesses")->check(CLI::Range(0u, 1000000u));
  cli.seed(o.seed, "component sizes and chaos");
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  return o;
}

std::vector<CaseResult> run_all(const Options& o) {
  std::vector<CaseResult> results;
  using Runner = CaseResult (*)(const Options&, WorkerId, SlotIndex, bool);
  const std::vector<std::pair<Runner, bool>> policies{{&run_case<PublicationOrders>, false},
                                                      {&run_case<BrokenReuseWithoutGrace>, true},
                                                      {&run_case<BrokenPublishEachSurface>, true}};
  const std::size_t total = policies.size() * o.threads.size() * o.slots.size();
  for (const auto& [run, negative] : policies) {
    for (WorkerId p : o.threads) {
      for (SlotIndex s : o.slots) {
        results.push_back(run(o, p, s, negative));
        const CaseResult& r = results.back();
        if (!o.quiet) {
          std::cerr << kProgram << ": [" << results.size() << "/" << total << "] " << r.policy << " P=" << p
                    << " slots=" << s << ": " << r.frames << " frames, " << r.seconds << " s, " << r.updates
                    << " updates, torn " << r.torn << ", reuse " << r.reuse << ", backwards " << r.backwards << " -> "
                    << (r.passed() ? (negative ? "caught" : "ok") : "UNEXPECTED") << "\n";
        }
      }
    }
  }
  return results;
}

report::Table case_table(const std::vector<CaseResult>& results) {
  report::Table t({{"policy", "policy", false}, {"threads", "P"}, {"slots", "slots"}, {"frames", "frames"},
                   {"seconds", "seconds"}, {"updates", "updates"}, {"driver_waits", "driver waits"}, {"torn", "torn"},
                   {"reuse", "reuse"}, {"backwards", "backwards"},
                   {"lag", "lag histogram (frames behind: draws)", false}, {"negative_control", "control", false},
                   {"passed", "passed", false}, {"verdict", "verdict", false}});
  for (const CaseResult& r : results) {
    std::ostringstream lag;
    report::Json lag_json = report::Json::object();
    for (const auto& [behind, n] : r.lag) {
      lag << (lag.tellp() > 0 ? ", " : "") << behind << ": " << n;
      lag_json[std::to_string(behind)] = n;
    }
    const std::string catch_time = std::to_string(r.frames) + " frames, " + report::fixed_text(r.seconds * 1e3, 1) + " ms";
    const std::string verdict = r.passed() ? (r.negative_control ? "caught (negative control) after " + catch_time : "ok")
                                           : (r.negative_control ? "FAIL: negative control not caught in " + catch_time : "FAIL");
    t.add_row({r.policy, r.threads, r.slots, r.frames, report::Cell::fixed(r.seconds, 3), r.updates, r.driver_waits,
               r.torn, r.reuse, r.backwards, report::Cell::shown_as(lag.str(), lag_json), r.negative_control,
               r.passed(), verdict});
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::vector<CaseResult> results = run_all(o);
  const bool ok = std::all_of(results.begin(), results.end(), [](const CaseResult& r) { return r.passed(); });
  const report::Table table = case_table(results);
  std::ostringstream md;
  md << "# Publication stress (measured, chaos " << o.chaos << " per million, " << o.seconds
     << " s per sound case; a negative control runs until caught, at most " << o.control_seconds << " s)\n\n"
     << table.markdown();
  report::Json js = report::document(kProgram, 2, "measured", FRONTSTEAL_GIT_COMMIT);
  js["chaos_per_million"] = o.chaos;
  js["cases"] = table.json();
  js["all_as_expected"] = ok;
  try {
    const report::ResultsDir dir(kProgram, o.out);
    dir.write("publication-stress.md", md.str());
    dir.write_json("publication-stress.json", js);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << "\n";
    return 1;
  }
  std::cout << table.terminal();
  return ok ? 0 : 1;
}
