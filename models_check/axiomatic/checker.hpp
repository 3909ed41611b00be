// checker.hpp — is a litmus program's final state reachable under a memory model? Every candidate execution
// (execution.hpp) is tried against the model's axioms (models.hpp); the answer is "allowed" with a witness
// execution, printed readably (events with their labels and values, rf and co edges), or "forbidden".
#pragma once

#include <optional>
#include <sstream>
#include <string>

#include "models_check/axiomatic/execution.hpp"
#include "models_check/axiomatic/models.hpp"

namespace frontsteal::axiomatic {

struct Verdict {
  bool allowed = false;
  long candidates = 0;               // candidate executions with well-defined values
  long consistent = 0;               // of those, consistent with the model
  std::optional<Execution> witness;  // a consistent execution that reaches the final state
};

inline Verdict check(const LitmusTest& test, Model model, ModelDefect defect = ModelDefect::none) {
  Verdict v;
  v.candidates = for_each_candidate(test, [&](const Execution& x) {
    if (!consistent(x, model, defect)) return true;
    ++v.consistent;
    if (reaches(x, test.final_state)) {
      v.allowed = true;
      v.witness = x;
      return false;  // one witness is enough
    }
    return true;
  });
  return v;
}

// "W x=1", "R y=0 (acq)", "F sc", "RMW-R c=0" …, with the instruction's site label when it has one.
inline std::string describe(const Execution& x, int e) {
  const Event& ev = x.events[e];
  const LitmusTest& t = *x.test;
  std::ostringstream s;
  if (ev.thread < 0) {
    s << "init " << t.locations[ev.location] << "=" << x.value[e];
    return s.str();
  }
  const Instruction& in = *ev.instruction;
  static constexpr const char* kOrder[] = {"rlx", "acq", "rel", "acq_rel", "sc"};
  const char* prefix = ev.is_rmw_part ? (ev.kind == EventKind::read ? "RMW-R " : "RMW-W ") : "";
  switch (ev.kind) {
    case EventKind::read:
      s << prefix << (ev.is_rmw_part ? "" : "R ") << t.locations[ev.location] << "=" << x.value[e];
      break;
    case EventKind::write:
      s << prefix << (ev.is_rmw_part ? "" : "W ") << t.locations[ev.location] << "=" << x.value[e];
      break;
    case EventKind::fence: s << "F"; break;
  }
  s << " (" << kOrder[static_cast<int>(in.order)] << ")";
  if (!in.label.empty()) s << " [" << in.label << "]";
  return s.str();
}

// The execution as text: each thread's events in program order, then the rf and co edges.
inline std::string describe(const Execution& x) {
  std::ostringstream s;
  for (int t = -1; t < static_cast<int>(x.test->threads.size()); ++t) {
    s << (t < 0 ? "  init:" : "  T" + std::to_string(t) + ":");
    for (int e = 0; e < x.event_count; ++e) {
      if (x.events[e].thread == t) s << "  e" << e << " " << describe(x, e) << ";";
    }
    s << "\n";
  }
  s << "  rf:";
  for (int a = 0; a < x.event_count; ++a) {
    for (int b = 0; b < x.event_count; ++b) {
      if (x.rf.has(a, b)) s << " e" << a << "→e" << b;
    }
  }
  s << "\n  co:";
  for (int a = 0; a < x.event_count; ++a) {
    if (x.events[a].thread < 0) continue;
    for (int b = 0; b < x.event_count; ++b) {
      if (x.co.has(a, b)) s << " e" << a << "→e" << b;
    }
  }
  s << "\n";
  return s.str();
}

}  // namespace frontsteal::axiomatic
