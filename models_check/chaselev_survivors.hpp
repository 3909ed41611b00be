// chaselev_survivors.hpp — the one-step weakenings of ChaseLev that survive every search, and why: data, as
// expected_verdicts.hpp is for the stealing protocol. A survivor not listed here, or a listed one that is
// killed, is an unexpected verdict of frontsteal-modelcheck-chaselev: the list must follow the evidence.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace frontsteal::model::chaselev {

struct ExpectedSurvivor {
  std::string_view mutant;  // e.g. "ChaseLev[B2:relaxed]"
  std::string_view why;
};

inline const std::vector<ExpectedSurvivor>& expected_survivors() {
  static const std::vector<ExpectedSurvivor> all{
      {"ChaseLev[B2:relaxed]",
       "needed on the C++ model, beyond Relacy: without it a thief's S4 may read the element the owner writes after "
       "seeing that thief's S5 (a load-buffering outcome), and Relacy never produces load buffering"},
      {"ChaseLev[K6:acq_rel]",
       "nothing found; by our reading of the C++20 model (P0668's coherence-ordered-before) the K3/S2 fences already "
       "order the owner against every thief, and the CAS needs only atomicity, which acq_rel keeps. Kept seq_cst as "
       "in the paper (proved for C11, whose fence rules were weaker); not a proof of redundancy"},
      {"ChaseLev[S1:relaxed]",
       "genuinely unnecessary on the C++ model: the seq_cst fence S2 right after S1 is also an acquire fence, so a "
       "relaxed S1 that reads a release store still synchronizes with it (fence-acquire). Kept acquire as in the "
       "paper"},
      {"ChaseLev[S5:acq_rel]",
       "nothing found; as for K6: the S2 fence orders the thief against the owner's K3, and the CAS needs only "
       "atomicity. Kept seq_cst as in the paper; not a proof of redundancy"},
  };
  return all;
}

// The listed survivor of that name, or nullptr.
inline const ExpectedSurvivor* find_survivor(const std::string& name) {
  for (const ExpectedSurvivor& s : expected_survivors()) {
    if (s.mutant == name) return &s;
  }
  return nullptr;
}

}  // namespace frontsteal::model::chaselev
