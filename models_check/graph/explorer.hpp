// explorer.hpp — stateless model checking of real code over execution graphs, in the style of GenMC and TruSt
// (Kokologiannakis, Raad, Vafeiadis, PLDI 2019; Kokologiannakis, Marmanis, Gladstein, Vafeiadis, POPL 2022).
//
// The program is ordinary C++ (core/ through graph_backend.hpp) whose threads run as fibers. Every atomic or
// plain access is an event of a growing execution graph. The explorer runs the lowest-numbered thread that can
// run until it finishes or blocks, and at each new event branches on every choice the memory model allows:
//   a read      reads from any write to its location already in the graph that keeps it consistent;
//   a write     takes any consistent place in its location's coherence order, and moreover REVISITS every earlier
//               read of the location that is not in its porf-prefix: the graph is cut back to the events added
//               before that read plus the write's porf-prefix, and the read now reads from the write (a read can
//               thus read from a write its own thread's run had not produced yet when the read first ran);
//   a fence     has no choice.
// Each branch is a graph; the explorer re-runs the program from the start and replays the graph in the order its
// events were added (reads return the values the graph gives them, so the program's unmodelled memory also holds
// what it held), then extends it. At each choice a fast necessary condition prunes (coherence_filter.hpp: RC11's
// hb-coherence and atomicity); the memory model's own axioms (models_check/axiomatic/models.hpp, on the whole graph)
// judge every run at its end and every failure before it is reported.
//
// EXPLORED ONCE. A backward revisit is taken only from the graph in which the revisited read and every event the
// revisit deletes were added MAXIMALLY (TruSt's condition, POPL 2022, §5, restated in explorer.cpp for this
// explorer's addition order): each read read the coherence-latest write before it or in the write's porf-prefix,
// each write went coherence-last among those, and no deleted read had been given its write by a revisit from
// outside that prefix. Every other graph that revisits to the same result is skipped, so each consistent execution
// is reached along one path: `complete` equals `distinct` (a hash of events, rf and co), which the validation
// checks on random programs of up to five threads. Completeness is held by the validation
// (tests/models_check/graph/explorer_test.cpp): every C++ program of the litmus catalogue, every protocol litmus
// program and hundreds of random programs have exactly the consistent executions the axiomatic checker enumerates,
// and each planted explorer defect breaks that (or, for the maximality condition, makes executions repeat).
//
// WHAT IS EXPLORED. Executions whose po ∪ rf is acyclic: RC11 exactly; ARMv8 through the standard mapping
// (program.hpp: LDAR or LDAPR for acquire loads) restricted to those executions, with no dependency assumed
// between a read and a later access (a compiler owes C++ code none), so every reordering ARMv8 allows without
// load buffering is explored. Load buffering (a read from a write that depends, through po ∪ rf, on the read) is
// not produced: the litmus tier (models_check/axiomatic/) decides those shapes.
//
// WAITS (spin-assume, as GenMC treats await loops). A wait that fails blocks its thread for the rest of this run
// instead of looping: a later write the wait could read REVISITS it, and that branch runs the thread on. A run
// that ends with blocked threads is a hang if every read of every blocked thread's failed wait reads the last
// write of its location (nothing the thread waits for can come); otherwise it is a blocked branch, discarded,
// because the branch in which the wait reads the newer write exists. What this gives up: a wait that fails
// several times with side effects in between (an idle round that takes and releases a free lock) is explored
// failing once; the Relacy tier's spin-bound argument (relacy_backend.hpp) applies unchanged.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/memory_order.hpp"
#include "core/site.hpp"
#include "models_check/graph/execution_graph.hpp"
#include "models_check/search.hpp"

namespace frontsteal::graph {

using model::Verdict;

enum class GraphModel : std::uint8_t { rc11, armv8_ldar, armv8_ldapr };
std::string_view name(GraphModel m);

struct Outcome {
  Verdict verdict = Verdict::kPass;
  std::string detail;
};

// A program for the explorer: setup() builds the shared state before the threads start (its stores are the
// locations' initial values), run_thread(t) is thread t's body, check() judges a complete execution.
class Program {
 public:
  virtual ~Program() = default;
  virtual int threads() const = 0;
  virtual void setup() = 0;
  virtual void run_thread(int t) = 0;
  virtual Outcome check(const Graph& g) = 0;
  virtual void teardown() = 0;
};

// Deliberate defects of the explorer, for its validation's negative controls: each must make the validation fail.
enum class ExplorerDefect : std::uint8_t {
  none,
  no_revisits,     // reads only read writes already in the graph: executions are lost
  co_last_only,    // a write only ever goes coherence-last: executions are lost
  no_final_check,  // runs are not judged by the model's axioms at their end: inconsistent ones are counted
  no_maximality,   // every backward revisit is taken: executions are explored more than once
};

struct ExploreOptions {
  GraphModel model = GraphModel::rc11;
  ExplorerDefect defect = ExplorerDefect::none;
  std::uint64_t max_executions = 0;  // complete + blocked + hung runs; 0: no bound
  double max_seconds = 0;            // 0: no bound
  bool stop_at_failure = true;
  // The exploration bound: at most `bound` writes at `bounded_site` per execution (0: none). Runs that would pass
  // it are cut and counted; the search is exhaustive for the executions within it.
  Site bounded_site = Site::kThiefShrinkEnd;
  int bound = 0;
  // Called about once a second: runs so far, complete executions so far, branches still to explore.
  std::function<void(std::uint64_t runs, std::uint64_t complete, std::size_t pending, double seconds)> progress;
};

struct ExploreResult {
  Outcome outcome;                      // the first failure, or pass
  std::string witness;                  // the failing execution, printed
  std::uint64_t complete = 0;           // executions in which every thread finished (checked)
  std::uint64_t distinct = 0;           // of those, distinct (events, rf, co)
  std::uint64_t blocked = 0;            // runs that ended with a wait the graph can still satisfy elsewhere (discarded)
  std::uint64_t hangs = 0;              // runs that ended with a wait nothing can satisfy
  std::uint64_t cut = 0;                // runs cut by the exploration bound
  std::uint64_t ended_early = 0;        // runs ended when a thread stopped for good (explorer.cpp: blocked for good)
  std::uint64_t revisits = 0;           // backward revisits explored
  std::uint64_t revisits_repeated = 0;  // revisits skipped because the graph had been explored
  std::uint64_t revisits_not_maximal = 0;  // revisits skipped by the maximality condition (explorer.cpp)
  std::uint64_t inconsistent = 0;          // choices rejected by the coherence filter (coherence_filter.hpp)
  std::uint64_t inconsistent_runs = 0;     // runs the model's axioms rejected at their end (the filter is weaker)
  std::size_t largest_graph = 0;           // events, initial writes included
  bool bounded = false;                    // stopped by max_executions or max_seconds: not exhaustive
  double seconds = 0;
};

ExploreResult explore(Program& program, const ExploreOptions& options);

// ---- the backend's interface (graph_backend.hpp); valid only inside explore() -----------------------------
struct Access {
  bool plain = false;
  Mo order = Mo::kRelaxed;
  bool has_site = false;
  Site site = Site::kOwnerAnnounce;
  const char* file = "";
  unsigned line = 0;
};
namespace runtime {
int new_location(Value initial, bool plain);
Value load(int location, const Access& a);
void store(int location, Value v, const Access& a);
// A read-modify-write: `update` gets the value read and returns the value to write, or nothing (a failed
// compare-exchange: then only the read happens). Returns the value read.
Value read_modify_write(int location, ax::Op op, const std::function<std::optional<Value>(Value)>& update,
                        const Access& a);
void fence(ax::Order order, const Access& a);
// How many events the calling thread has so far (a program's ghost marker of where something happened).
std::size_t events_so_far();
// The run is not an execution of the program unless `holds` (a litmus compare-exchange off its success path):
// when false, the run is dropped without a verdict. Does not return when false.
void assume(bool holds);
// A wait's iteration failed at `site`: the thread blocks (spin-assume). Does not return.
[[noreturn]] void wait_failed(Site site);
// A protocol invariant or a program's assertion failed. Does not return.
[[noreturn]] void fail(Verdict v, const std::string& what, const char* file, unsigned line);
}  // namespace runtime

// "R Front=3 (acq) [T5]  core/stealing_protocol.hpp:245", per thread, then rf and co.
std::string describe(const Graph& g);

}  // namespace frontsteal::graph
