// expected_verdicts.hpp — what each policy must do in each scenario, as data.
//
// A cell is the set of verdicts that count as expected. Exactly-once policies must pass every scenario in the
// exactly-once check. Paper must be *caught* (a duplicate) wherever an owner can be claiming while a thief
// steals from it — every scenario with at least one item — and must pass the at-least-once check everywhere.
// The negative controls are expected to be caught exactly where Paper is: their defects open the same
// window without any help from weak memory.
#pragma once

#include <string_view>
#include <vector>

#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::model {

struct Expectation {
  std::vector<Verdict> accepted;
  std::string_view why;
};

inline Expectation expected_verdict(const PolicyTable& policy, const ScenarioSpec& scenario, CheckMode mode) {
  const bool faulty = policy.contract == Contract::kAtLeastOnce || policy.defects != Defect::kNone;
  // The termination check runs in both modes, so this control is expected to fail in both.
  if (has(policy.defects, Defect::kThiefJoinsLate) && scenario.items != 0) {
    return {{Verdict::kEarlyQuit}, "negative control: a worker quits while a stolen share is uncounted"};
  }
  if (mode == CheckMode::kAtLeastOnce) return {{Verdict::kPass}, "every policy is at least at-least-once"};
  if (!faulty) return {{Verdict::kPass}, "exactly-once contract"};
  if (scenario.items == 0) return {{Verdict::kPass}, "no item, nothing to duplicate"};
  if (has(policy.defects, Defect::kShareLowerBound)) {
    bool several_entries = false;
    for (const RangeList& list : scenario.initial) several_entries = several_entries || list.size() > 1;
    if (several_entries) return {{Verdict::kDuplicate}, "negative control: a share spanning entries copies ids below"};
    // One-entry lists: the entry holding mid is the only one, and there the wrong bound equals the right one.
    // A list a thief installs from a share is one entry again (append_merging). A second frame's list is the
    // worker's log of the first (frame_loop.hpp, normalized) and can have two entries, but the multi-frame
    // scenarios have at most 3 items: a two-entry list there has at most 2 items, and mid = front + 1 then
    // lies in its last entry, where the bounds agree again. A bigger multi-frame scenario may need
    // {pass, duplicate} here; a wrong expectation fails the run, so it cannot hide a bug.
    return {{Verdict::kPass}, "one entry per list: the wrong lower bound is never used (invisible here)"};
  }
  if (has(policy.defects, Defect::kBatchIgnoresEnd)) {
    if (scenario.claim_batch > 1) return {{Verdict::kDuplicate}, "negative control: a batch claims past End"};
    return {{Verdict::kPass}, "single claims: a batch of one never passes End (invisible here)"};
  }
  if (policy.defects != Defect::kNone) return {{Verdict::kDuplicate}, "negative control: the defect must be caught"};
  return {{Verdict::kDuplicate}, "at-least-once: store buffering at the handshake duplicates an item"};
}

}  // namespace frontsteal::model
