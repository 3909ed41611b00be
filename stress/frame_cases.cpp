// frame_cases.cpp — frontsteal-stress's frame-level case: run, audit, judge, print.
#include "stress/frame_cases.hpp"

#include <chrono>
#include <cstdio>
#include <random>
#include <sstream>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/synthetic_work.hpp"
#include "reporting/table.hpp"
#include "stress/chaos_backend.hpp"
#include "stress/stress_targets.hpp"

namespace frontsteal::stress {

namespace {

// Random, skewed costs that change every frame: a hot window (1/8 of the items, 20x) at a random place,
// and per-item jitter of 1-8 units.
class CostModel {
 public:
  CostModel(ItemId items, std::uint64_t seed) : costs_(items), rng_(seed) {}
  void next_frame() {
    if (costs_.empty()) return;
    const ItemId hot = static_cast<ItemId>(rng_() % costs_.size());
    for (ItemId i = 0; i < costs_.size(); ++i) {
      const bool is_hot = (i - hot) % costs_.size() < costs_.size() / 8 + 1;
      costs_[i] = static_cast<std::uint32_t>((1 + rng_() % 8) * (is_hot ? 20 : 1) * 8);
    }
  }
  std::uint32_t cost(ItemId i) const { return costs_[i]; }

 private:
  std::vector<std::uint32_t> costs_;
  std::mt19937_64 rng_;
};

}  // namespace

CaseResult run_case(const TargetInfo& t, WorkerId p, const Options& o, std::uint32_t cost_scale) {
  CaseResult r;
  r.target = t.name;
  r.contract = std::string(name(t.contract));
  r.negative_control = t.negative_control;
  r.threads = p;
  r.items = o.items;
  auto target = t.make(p, o.items, o.seed + p);
  ExecutionCounter runs(o.items);
  CostModel costs(o.items, o.seed * 7919 + p);
  const std::uint64_t chaos_before = chaos_injections().load();
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  auto last_report = start;
  // How often a planted defect shows is a matter of timing: on a loaded machine the workers may rarely overlap.
  // So a negative control runs until its first duplicate, not for a fixed time; control_seconds is only there
  // so that a defect the audit cannot see ends the run (as a failure) instead of hanging it.
  auto finished = [&] {
    if (t.negative_control) return r.duplicated > 0 || elapsed() >= o.control_seconds;
    return o.frames ? r.frames >= o.frames : elapsed() >= o.seconds;
  };
  while (!finished()) {
    costs.next_frame();
    const auto& st = target->run_frame([&](ItemId id, WorkerId) {
      runs.record(id);
      spin_work(costs.cost(id) * cost_scale);
    });
    const ExecutionAudit a = runs.audit_and_reset();
    ++r.frames;
    r.lost += a.lost;
    r.duplicated += a.duplicated;
    (a.duplicated == 0 ? r.frames_dup0 : a.duplicated == 1 ? r.frames_dup1 : r.frames_dup2plus)++;
    r.steals += st.totals().steals_succeeded;
    r.skipped += st.totals().items_skipped;
    if (!o.quiet && std::chrono::steady_clock::now() - last_report > std::chrono::seconds(5)) {
      last_report = std::chrono::steady_clock::now();
      std::fprintf(stderr, "    ... %s P=%u: %llu frames\n", t.name.c_str(), p,
                   static_cast<unsigned long long>(r.frames));
    }
  }
  r.seconds = elapsed();
  r.chaos = chaos_injections().load() - chaos_before;
  if (r.lost > 0) {
    r.passed = false;
    r.verdict = "FAIL: lost items";
  } else if (t.negative_control) {
    r.passed = r.duplicated > 0;
    std::ostringstream v;
    v << (r.passed ? "caught (negative control) after " : "FAIL: negative control not caught in ") << r.frames
      << " frames, " << report::fixed_text(r.seconds * 1e3, 1) << " ms";
    r.verdict = v.str();
  } else if (t.contract == Contract::kExactlyOnce && r.duplicated > 0) {
    r.passed = false;
    r.verdict = "FAIL: duplicates under an exactly-once policy";
  } else {
    r.verdict = t.contract == Contract::kExactlyOnce ? "exactly-once held" : "at-least-once held";
  }
  return r;
}

void print_case(const CaseResult& c) {
  std::printf("%-30s P=%-2u frames %8llu | dup 0:%llu 1:%llu 2+:%llu | lost %llu | %8.3f dup/1e6 items | %s\n",
              c.target.c_str(), c.threads, static_cast<unsigned long long>(c.frames),
              static_cast<unsigned long long>(c.frames_dup0), static_cast<unsigned long long>(c.frames_dup1),
              static_cast<unsigned long long>(c.frames_dup2plus), static_cast<unsigned long long>(c.lost),
              c.duplicates_per_million_items(), c.verdict.c_str());
  std::fflush(stdout);
}

}  // namespace frontsteal::stress
