// fault_scenarios.cpp — the three fault scenarios of frontsteal-stress.
#include "stress/fault_scenarios.hpp"

#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <utility>

#include "core/execution_counter.hpp"
#include "core/policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/synthetic_work.hpp"
#include "stress/watchdog.hpp"
#include "stress/chaos_backend.hpp"

namespace frontsteal::stress {

namespace {

// (a) A worker stalls mid-frame while holding most of the work: the others finish the frame by stealing.
FaultResult fault_stall(const Options& o) {
  const WorkerId p = 3;
  const ItemId n = 3000;
  StealingScheduler<Fenced, ChaosBackend> s({.workers = p, .items = n, .seed = o.seed});
  const Watchdog dog = watch_workers(s, "frontsteal-stress: fault stall");
  s.reseed({{{0, 2700}}, {{2700, 2850}}, {{2850, 3000}}});  // worker 0 holds 90%
  ExecutionCounter runs(n);
  const auto stall = std::chrono::milliseconds(40);
  const auto& st = s.run_frame([&](ItemId id, WorkerId) {
    runs.record(id);
    if (id == 0) std::this_thread::sleep_for(stall);  // worker 0's first item: it stalls holding 2699 more
    spin_work(200);
  });
  const auto a = runs.audit_and_reset();
  const std::uint64_t by_others = st.workers[1].items_processed + st.workers[2].items_processed;
  std::ostringstream d;
  d << "frame " << st.wall_ns / 1e6 << " ms with a " << stall.count() << " ms stall; worker 0 ran "
    << st.workers[0].items_processed << " items, the others " << by_others << "; " << a;
  return {"stall: a worker stalls holding 90% of the items", a.exactly_once() && by_others > 2000, d.str()};
}

// (b) An item throws: the frame ends, the caller gets the item id, the next frame loses nothing.
FaultResult fault_throw(const Options& o) {
  const ItemId n = 500;
  StealingScheduler<Fenced, ChaosBackend> s({.workers = 3, .items = n, .seed = o.seed});
  const Watchdog dog = watch_workers(s, "frontsteal-stress: fault throw");
  ExecutionCounter runs(n);
  std::ostringstream d;
  bool ok = false;
  try {
    s.run_frame([&](ItemId id, WorkerId) {
      runs.record(id);
      if (id == 317) throw std::runtime_error("injected fault");
    });
    d << "no ItemError reached the caller";
  } catch (const ItemError& e) {
    const auto first = runs.audit_and_reset();
    s.run_frame([&](ItemId id, WorkerId) { runs.record(id); });
    const auto second = runs.audit_and_reset();
    ok = e.item() == 317 && first.exactly_once() && second.exactly_once();
    d << "caller got: \"" << e.what() << "\"; that frame: " << first << "; next frame: " << second;
  }
  return {"throw: an item function throws", ok, d.str()};
}

// (c) P = 1, and P larger than the item count.
FaultResult fault_edges(const Options& o) {
  std::ostringstream d;
  bool ok = true;
  for (auto [p, n] : {std::pair<WorkerId, ItemId>{1, 200}, {8, 3}, {4, 0}}) {
    StealingScheduler<Fenced, ChaosBackend> s({.workers = p, .items = n, .seed = o.seed});
    const Watchdog dog =
        watch_workers(s, "frontsteal-stress: fault edges, P=" + std::to_string(p) + " N=" + std::to_string(n));
    ExecutionCounter runs(n);
    std::uint64_t bad = 0;
    for (int f = 0; f < 300; ++f) {
      s.run_frame([&](ItemId id, WorkerId) { runs.record(id); });
      bad += runs.audit_and_reset().exactly_once() ? 0 : 1;
    }
    d << "P=" << p << " N=" << n << ": " << bad << " bad frames of 300; ";
    ok = ok && bad == 0;
  }
  return {"edges: P = 1, P > N, N = 0", ok, d.str()};
}

}  // namespace

std::vector<FaultResult> run_faults(const Options& o) {
  std::vector<FaultResult> results;
  for (auto fault : {fault_stall, fault_throw, fault_edges}) {
    FaultResult f = fault(o);
    std::printf("fault %-45s %s  %s\n", f.name.c_str(), f.passed ? "pass" : "FAIL", f.detail.c_str());
    results.push_back(f);
  }
  return results;
}

}  // namespace frontsteal::stress
