// publication_suite.cpp — Relacy model of greedy rendering's publication and reclamation
// (core/component_publication.hpp) under a run-time policy table. The only publication file that includes Relacy.
//
// Threads: 0 the pusher, 1 the driver and tessellator 0, 2 tessellator 1. Triangles are modelled by one rl::var
// per (component, slot, surface) holding the frame that wrote it, so
//   - a pusher read of a slot that a tessellator is rewriting, without happens-before, is a data race
//     (use after reuse; Relacy reports it),
//   - a published slot whose surfaces hold different frames is a torn component (the pusher asserts),
//   - a component going back to an older frame, or not showing the last frame at the end, is caught too.
#include <cstdio>

#include "core/component_publication.hpp"
#include "models_check/publication_check.hpp"
#include "models_check/protocol_suite.hpp"  // last group: includes Relacy

namespace frontsteal::model {
namespace {

const PublicationSpec* g_spec = nullptr;

struct PublicationSuite : rl::test_suite<PublicationSuite, 3> {
  using Publication = ComponentPublication<RelacyBackend, TablePolicy>;

  const PublicationSpec& spec = *g_spec;
  std::unique_ptr<Publication> publication;
  rl::var<int> data[kMaxPublicationComponents][kMaxPublicationSlots][kMaxPublicationSurfaces];
  rl::atomic<int> go;        // harness: frame k released to tessellator 1
  rl::atomic<int> finished;  // harness: tessellators done with their surfaces, over all frames
  bool collapsed = false;

  // Heap traffic bypasses Relacy's allocator for the whole execution (HeapOutsideRelacy, protocol_suite.hpp):
  // the suite's own vectors would otherwise make every free() a choice point.
  ~PublicationSuite() {
    publication.reset();
    --HeapOutsideRelacy::counter();
  }

  void before() {
    ++HeapOutsideRelacy::counter();
    spin_bound().discarded = false;
    SuiteContext& ctx = suite_context();
    if (ctx.execution_cap != 0 && ++ctx.executions > ctx.execution_cap) {
      collapsed = true;
      return;
    }
    std::vector<std::uint32_t> sizes;
    for (const auto& c : spec.components) sizes.push_back(static_cast<std::uint32_t>(c.size()));
    publication = std::make_unique<Publication>(sizes, spec.slots);
    for (auto& c : data)
      for (auto& s : c)
        for (auto& v : s) v($) = 0;
    go.store(0, rl::mo_relaxed, $);
    finished.store(0, rl::mo_relaxed, $);
  }

  void thread(unsigned index) {
    if (collapsed) return;
    // Landing point for a discarded execution (relacy_backend.hpp, SPIN BOUND).
    if (setjmp(spin_bound().exits[index]) != 0) return;
    if (index == 0) return pusher();
    tessellator(index - 1);
  }

  void pusher() {
    int last_seen[kMaxPublicationComponents] = {};
    for (std::uint32_t u = 0; u < spec.updates; ++u) {
      publication->begin_update();
      for (ComponentId c = 0; c < spec.components.size(); ++c) {
        const SlotIndex s = publication->read(c);
        if (s == Publication::kNothing) continue;
        const int first = data[c][s][0]($);
        for (std::size_t i = 1; i < spec.components[c].size(); ++i) {
          if (data[c][s][i]($) != first) fail_with(Verdict::kOtherFailure, "torn component: surfaces of two frames", $);
        }
        if (first == 0) fail_with(Verdict::kOtherFailure, "pusher drew a slot no frame has finished", $);
        if (first < last_seen[c]) fail_with(Verdict::kOtherFailure, "a component went back to an older frame", $);
        last_seen[c] = first;
      }
      publication->end_update();
    }
  }

  // The harness's own waits fall under the spin bound like the protocol's (a frame-long wait: one extra
  // failure, as E2/E6): otherwise the tree searches would not be finite.
  template <class Ready>
  static void await(Ready ready) {
    for (std::uint32_t failures = 1;; ++failures) {
      spin_bound().stop_if_discarded();
      if (ready()) return;
      spin_bound().failed_iteration(failures, true);
      rl::yield(1, $);
    }
  }

  void tessellator(std::uint32_t me) {
    const int writers = 2;
    for (int k = 1; k <= static_cast<int>(spec.frames); ++k) {
      if (me == 0) {
        await([&] { return finished.load(rl::mo_acquire, $) >= writers * (k - 1); });
        publication->prepare_frame();
        go.store(k, rl::mo_release, $);
      } else {
        await([&] { return go.load(rl::mo_acquire, $) >= k; });
      }
      for (ComponentId c = 0; c < spec.components.size(); ++c) {
        for (std::size_t i = 0; i < spec.components[c].size(); ++i) {
          if (spec.components[c][i] != me) continue;
          data[c][publication->back_slot(c)][i]($) = k;  // this surface's triangles for frame k
          publication->finish_surface(c);
        }
      }
      finished.fetch_add(1, rl::mo_acq_rel, $);
    }
  }

  void after() {
    if (collapsed) return;
    if (spin_bound().discarded) {  // a wait exceeded the bound: not a complete execution, nothing to check
      ++suite_context().discarded;
      return;
    }
    ++suite_context().completed;
    for (ComponentId c = 0; c < spec.components.size(); ++c) {
      const SlotIndex s = publication->read(c);
      for (std::size_t i = 0; i < spec.components[c].size(); ++i) {
        if (s == Publication::kNothing || data[c][s][i]($) != static_cast<int>(spec.frames)) {
          fail_with(Verdict::kLost, "the last frame is not what is published at the end", $);
        }
      }
    }
  }
};

}  // namespace

SearchResult run_publication(const PublicationSpec& spec, const SearchConfig& config) {
  g_spec = &spec;
  return simulate_suite<PublicationSuite>(spec.name, config);
}

}  // namespace frontsteal::model
