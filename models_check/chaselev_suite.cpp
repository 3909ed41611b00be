// chaselev_suite.cpp — Relacy model of the Chase–Lev deque (core/chase_lev_deque.hpp) under a run-time policy
// table. The only Chase–Lev file that includes Relacy.
//
// Items are indices 0..n-1 carried by the deque. Before pushing item i the owner writes payload[i], an rl::var;
// whoever gets i (the owner's take, a thief's steal, or the final drain) reads it. So
//   - an item handed over without happens-before from its push is a data race on the payload (Relacy reports it),
//   - an item returned twice is a duplicate (ghost count, checked in interleaving order),
//   - an item pushed but never returned, even by the final drain, is lost,
//   - a value that is no pushed item (a torn or stale slot) is a failure.
#include <cstdio>

#include "core/chase_lev_deque.hpp"
#include "models_check/chaselev_check.hpp"
#include "models_check/protocol_suite.hpp"  // last group: includes Relacy

namespace frontsteal::model {
namespace {

const ChaseLevSpec* g_spec = nullptr;

template <rl::thread_id_t Threads>
struct ChaseLevSuite : rl::test_suite<ChaseLevSuite<Threads>, Threads> {
  using Deque = ChaseLevDeque<std::uint32_t, RelacyBackend, TablePolicy>;

  const ChaseLevSpec& spec = *g_spec;
  std::unique_ptr<Deque> deque;
  rl::var<int> payload[kMaxChaseLevItems];
  // Ghost state, plain: Relacy runs every thread on fibers of one OS thread, so these follow the interleaving.
  bool pushed[kMaxChaseLevItems] = {};
  int got[kMaxChaseLevItems] = {};
  bool collapsed = false;

  // Heap traffic bypasses Relacy's allocator (see HeapOutsideRelacy in protocol_suite.hpp): its frees are choice
  // points that would multiply the tree searches for nothing (the deque frees no shared memory).
  ~ChaseLevSuite() {
    deque.reset();
    --HeapOutsideRelacy::counter();
  }

  void before() {
    ++HeapOutsideRelacy::counter();
    SuiteContext& ctx = suite_context();
    spin_bound().discarded = false;
    if (ctx.execution_cap != 0 && ++ctx.executions > ctx.execution_cap) {
      collapsed = true;
      return;
    }
    deque = std::make_unique<Deque>(spec.capacity);
    for (auto& p : payload) p($) = 0;
  }

  void thread(unsigned index) {
    if (collapsed) return;
    // Landing point should the spin bound discard an execution (relacy_backend.hpp). The deque never waits, so
    // nothing here calls spin_pause and no execution is discarded; the landing point keeps that an assumption
    // that fails safe rather than a longjmp to nowhere.
    if (setjmp(spin_bound().exits[index]) != 0) return;
    if (index == 0) return owner();
    for (std::uint32_t a = 0; a < spec.steal_attempts; ++a) {
      std::uint32_t x = 0;
      if (deque->steal(x) == StealResult::kSuccess) consume(x, "thief");
    }
  }

  void owner() {
    std::uint32_t next = 0;
    for (char op : spec.owner_ops) {
      if (op == 'P') {
        const std::uint32_t i = next++;
        payload[i]($) = static_cast<int>(i) + 1;  // what the consumer of item i must see
        pushed[i] = deque->push(i);  // a refused push (full from the owner's view) is legal: i is not expected
      } else {
        std::uint32_t x = 0;
        if (deque->take(x)) consume(x, "owner");
      }
    }
  }

  void consume(std::uint32_t x, const char* who) {
    char text[120];
    if (x >= kMaxChaseLevItems || !pushed[x]) {
      std::snprintf(text, sizeof text, "%s got %u, which is no pushed item", who, x);
      fail_with(Verdict::kOtherFailure, text, $);
      return;
    }
    if (got[x]++ != 0) {
      std::snprintf(text, sizeof text, "item %u returned twice (second time to the %s)", x, who);
      fail_with(Verdict::kDuplicate, text, $);
    }
    if (payload[x]($) != static_cast<int>(x) + 1) fail_with(Verdict::kOtherFailure, "stale payload", $);
  }

  void after() {
    if (collapsed) return;
    // The deque never waits, so no execution is discarded today; if one were, after() must not call into the
    // backend (stop_if_discarded would longjmp into a thread body that has already returned).
    if (spin_bound().discarded) {
      ++suite_context().discarded;
      return;
    }
    std::uint32_t x = 0;
    for (std::uint32_t k = 0; k < kMaxChaseLevItems && deque->take(x); ++k) consume(x, "final drain");
    for (std::uint32_t i = 0; i < kMaxChaseLevItems; ++i) {
      if (pushed[i] && got[i] == 0) {
        char text[80];
        std::snprintf(text, sizeof text, "item %u pushed but never returned", i);
        fail_with(Verdict::kLost, text, $);
      }
    }
    ++suite_context().completed;
  }
};

}  // namespace

SearchResult run_chaselev(const ChaseLevSpec& spec, const SearchConfig& config) {
  g_spec = &spec;
  if (spec.thieves == 1) return simulate_suite<ChaseLevSuite<2>>(spec.name, config);
  return simulate_suite<ChaseLevSuite<3>>(spec.name, config);
}

}  // namespace frontsteal::model
