// negative_controls.hpp — deliberately broken protocol variants.
//
// Every exactly-once check in frontsteal (Catch2, stress, model checker) runs against at least one of these
// and must report a failure; a check that passes them is a check that cannot fail. They keep Fenced's
// orders, so the only fault is the named defect. They claim exactly-once on purpose: the checks must catch
// the lie.
#pragma once

#include "core/policies.hpp"

namespace frontsteal {

// The thief keeps its whole share without waiting on ListTransient or re-reading Front (drops T4, T5): the
// item the victim claimed just before the steal runs twice.
struct BrokenSkipsReread : Fenced {
  static constexpr std::string_view kName = "Broken:SkipsReread";
  static constexpr Defect defects() noexcept { return Defect::kSkipFrontReread; }
};

// The owner claims without raising ListTransient (drops O1, O4): a thief re-reads Front while a claim is in
// flight, and misses it.
struct BrokenNoTransient : Fenced {
  static constexpr std::string_view kName = "Broken:NoTransient";
  static constexpr Defect defects() noexcept { return Defect::kOwnerSkipsTransient; }
};

}  // namespace frontsteal
