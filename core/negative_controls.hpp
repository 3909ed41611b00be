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

// The thief joins the active-worker count after lowering the victim's End (A1 after T3): between the two,
// the victim can exhaust its shortened list and leave, the count reaches 0 while the stolen share is held by
// nobody counted, and idle workers quit the frame while stealable work remains. Every item still runs once
// (the thief installs and drains its share), so only a termination check catches it.
struct BrokenJoinsLate : Fenced {
  static constexpr std::string_view kName = "Broken:JoinsLate";
  static constexpr Defect defects() noexcept { return Defect::kThiefJoinsLate; }
};

// The share copy takes mid as the lower bound of every list entry it copies, instead of max(mid, the entry's
// start). For the entry that holds mid the two agree, so with one-range lists nothing changes; an entry that
// starts above mid is copied from below its own start (unsigned wrap), handing the thief ids of an earlier
// entry, which the victim also runs. Only a scenario whose steal spans several entries can catch it
// (models_check multi_range_steal).
struct BrokenShareLowerBound : Fenced {
  static constexpr std::string_view kName = "Broken:ShareLowerBound";
  static constexpr Defect defects() noexcept { return Defect::kShareLowerBound; }
};

// The owner raises ListTransient (O1) and never lowers it (drops O4). Every item still runs exactly once, and
// nothing is lost; but the first thief of this owner waits at T4 forever, holding the victim's LockList and
// counted as active, so the frame never ends. Not an audit's negative control: the watchdog's
// (stress/watchdog.hpp). Tests that use it force the steal (tests/core/stealing_scheduler_test.cpp).
struct BrokenNeverRetracts : Fenced {
  static constexpr std::string_view kName = "Broken:NeverRetracts";
  static constexpr Defect defects() noexcept { return Defect::kOwnerNeverRetracts; }
};

// A batched claim (Owner::try_claim_up_to) takes up to n positions bounded by its list entry, forgetting the End
// it read at O2. A claim that overlaps a steal is still corrected by the thief's re-read of Front; a claim that
// begins after a steal has ended takes positions the thief already keeps, which then run twice. Invisible to
// single claims (n = 1 never passes End), so only a scenario whose owner claims in batches can catch it
// (models_check owner_batch_vs_thief).
struct BrokenBatchIgnoresEnd : Fenced {
  static constexpr std::string_view kName = "Broken:BatchIgnoresEnd";
  static constexpr Defect defects() noexcept { return Defect::kBatchIgnoresEnd; }
};

}  // namespace frontsteal
