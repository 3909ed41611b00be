// scenarios.hpp — the protocol scenarios, as data: one source for the model checker (Relacy), and for the
// stress driver and tests that want the same configurations.
//
// Each scenario is a small configuration of the whole frame loop: workers, items, frames, the initial lists,
// optional victim orders, and whether a caller thread hands frames over (E1/E2, E5/E6). Sizes are small on
// purpose: Relacy explores interleavings exhaustively within a bound, so three items already give it
// thousands of distinct executions.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::model {

struct ScenarioSpec {
  std::string_view name;
  std::string_view checks;  // one line: the property this scenario exists for
  WorkerId workers;
  ItemId items;
  std::uint32_t frames;
  std::vector<RangeList> initial;              // one list per worker
  std::vector<std::vector<WorkerId>> victims;  // empty: the seeded random orders
  bool with_caller = false;                    // an extra thread releases frames and reads the results
  std::uint32_t claim_batch = 1;               // positions per owner handshake (StealingWorkers::set_claim_batch)
  WorkerId threads() const { return workers + (with_caller ? 1 : 0); }
};

inline constexpr ItemId kMaxScenarioItems = 8;
inline constexpr std::uint32_t kMaxScenarioFrames = 2;

inline const std::vector<ScenarioSpec>& scenarios() {
  static const std::vector<ScenarioSpec> all{
      {"owner_vs_thief",
       "one owner, one thief: the ListTransient handshake and the re-read of Front",
       2,
       3,
       1,
       {{{0, 3}}, {}},
       {}},
      {"owner_vs_two_thieves",
       "two thieves of one victim: exclusion by the LockList try-lock",
       3,
       3,
       1,
       {{{0, 3}}, {}, {}},
       {}},
      {"thief_chain",
       "stealing from a thief: worker 2 tries worker 1 (itself a thief of 0) first",
       3,
       4,
       1,
       {{{0, 4}}, {}, {}},
       {{1, 2}, {0, 2}, {1, 0}}},
      {"two_frames",
       "lists carried over to a second frame; payloads ordered across the frame boundary",
       2,
       3,
       2,
       {{{0, 2}}, {{2, 3}}},
       {}},
      {"termination",
       "termination without a master: an idle worker from the start, then a frame boundary",
       3,
       2,
       2,
       {{{0, 1}}, {{1, 2}}, {}},
       {}},
      {"caller_handoff",
       "a caller thread releases frames and reads results (E1/E2, E5/E6)",
       2,
       2,
       2,
       {{{0, 2}}, {}},
       {},
       true},
      {"edge_empty", "empty lists: every worker idle at once, frames still end", 2, 0, 2, {{}, {}}, {}},
      {"edge_one_item", "one item: owner and thief race for it", 2, 1, 1, {{{0, 1}}, {}}, {}},
      {"multi_range_steal",
       "a list of four one-item entries, not in id order: the share spans several entries",
       2,
       4,
       1,
       {{{0, 1}, {2, 3}, {1, 2}, {3, 4}}, {}},
       {}},
      {"owner_batch_vs_thief",
       "one owner claiming up to three items per handshake (Owner::try_claim_up_to), one thief",
       2,
       4,
       1,
       {{{0, 4}}, {}},
       {},
       false,
       3},
      {"edge_victim_finishing",
       "both lists nearly done: a victim finishes while being stolen from",
       2,
       3,
       1,
       {{{0, 2}}, {{2, 3}}},
       {}},
  };
  return all;
}

}  // namespace frontsteal::model
