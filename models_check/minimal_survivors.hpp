// minimal_survivors.hpp — the one-step weakenings of Minimal that every Relacy search lets through, and why:
// data, as expected_verdicts.hpp is for the verdicts and chaselev_survivors.hpp for Chase-Lev. Each is needed
// beyond Relacy's reach — Relacy never produces load buffering — and the axiomatic checker kills it
// (models_check/axiomatic/litmus_certificate.hpp; tests/models_check/axiomatic/protocol_litmus_test.cpp holds
// the list to that evidence). Relacy's certificate of Minimal counts a listed survivor as killed there; a
// survivor not listed, or a listed weakening that Relacy kills, leaves Minimal uncertified: the list must follow
// the evidence.
#pragma once

#include <string_view>
#include <vector>

#include "core/memory_order.hpp"
#include "core/site.hpp"

namespace frontsteal::model {

struct NeededBeyondRelacy {
  Site site;
  Mo order;                 // Minimal's order at the site; one step weaker survives Relacy
  std::string_view path;    // the litmus path on which the axiomatic checker kills the weakening
  std::string_view killed;  // the models under which it does
  std::string_view why;
};

inline const std::vector<NeededBeyondRelacy>& minimal_survivors() {
  static const std::vector<NeededBeyondRelacy> all{
      {Site::kThiefShrinkEnd, Mo::kRelease, "termination", "C++ with load buffering, ARMv8",
       "the thief's join (A1) must happen-before any victim that sees its End store (T3): otherwise the victim's "
       "leave (A2) may be ordered first, the count touches 0 while a share is uncounted, and an idle worker quits "
       "early"},
      {Site::kOwnerReadEnd, Mo::kAcquire, "termination", "C++ with load buffering",
       "the victim's read of End (O2) must acquire the thief's T3 so that A1 happens-before A2; on ARMv8 the "
       "branch on O2 orders A2's write already (ctrl;[W]), under C++ nothing does"},
  };
  return all;
}

// The listed survivor at `site`, or nullptr.
inline const NeededBeyondRelacy* find_minimal_survivor(Site site) {
  for (const NeededBeyondRelacy& s : minimal_survivors()) {
    if (s.site == site) return &s;
  }
  return nullptr;
}

}  // namespace frontsteal::model
