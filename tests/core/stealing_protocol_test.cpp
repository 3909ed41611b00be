// Deterministic interleavings of the protocol (core/stealing_protocol.hpp), one step at a time from one thread.
//
// Each test drives an owner and a thief through their labelled steps in a chosen order. Orders a policy's
// memory model forbids are not driven for that policy: the store-buffering order (the owner's O1 still in its
// store buffer when it loads End at O2) is driven only where forbids_store_buffering<Policy>() is false.
// That decision is the static reading of the policy; models_check/ and stress/ test it dynamically.
#include "core/stealing_protocol.hpp"

#include <catch2/catch.hpp>

#include <optional>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/frame_loop.hpp"
#include "core/membarrier.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "core/std_backend.hpp"

namespace fs = frontsteal;
using fs::IdRange;
using fs::RangeList;
using fs::StealOutcome;

namespace {

// Catch2 v2 has no SKIP: a policy the kernel cannot support warns (visible in the output) and returns.
template <class Policy>
bool policy_usable() {
  if constexpr (Policy::kNeedsMembarrier) {
    if (!fs::membarrier_status().available) {
      WARN("skipped " << Policy::kName << ": " << fs::membarrier_status().detail);
      return false;
    }
  }
  return true;
}

// Two workers (0 = victim/owner, 1 = thief) on one thread, plus a ledger of which worker ran which item.
template <class Policy>
struct Stage {
  explicit Stage(fs::ItemId items, fs::WorkerId workers = 2) : core(workers, items, 7), runs(items) {}

  auto& owner(fs::WorkerId w = 0) { return core.owner(w); }
  auto& thief(fs::WorkerId w = 1) { return core.thief(w); }
  auto& slot(fs::WorkerId w = 0) { return core.slot(w); }

  // Owner w claims one item completely and "runs" it.
  std::optional<fs::ItemId> claim(fs::WorkerId w = 0) {
    const auto id = owner(w).try_claim();
    if (id) runs.record(*id);
    return id;
  }
  // Owner w runs everything left on its list.
  void drain(fs::WorkerId w) {
    while (claim(w)) {
    }
  }
  // The thief's whole kept share "runs" and becomes its list (as the frame loop does).
  void install_share(fs::WorkerId w = 1) { owner(w).install(thief(w).share()); }

  fs::StealingWorkers<fs::StdBackend, Policy> core;
  fs::ExecutionCounter runs;
};

}  // namespace

TEMPLATE_TEST_CASE("a steal without overlap takes the second half and leaves the first", "[core][protocol]", fs::SeqCst,
                   fs::Paper, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  Stage<TestType> s(10);
  s.owner().install(RangeList{{0, 3}, {3, 6}, {6, 10}});  // 10 items in three ranges
  REQUIRE(s.claim() == 0u);
  REQUIRE(s.claim() == 1u);
  REQUIRE(s.thief().try_steal(s.slot()) == StealOutcome::kStolen);  // 8 unclaimed: thief takes 4
  CHECK(s.thief().share().size() == 1);
  CHECK(s.thief().share()[0] == IdRange{6, 10});
  CHECK(s.thief().skipped() == 0u);
  s.install_share();
  s.drain(0);
  s.drain(1);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK(audit.exactly_once());
}

TEMPLATE_TEST_CASE("the thief waits on ListTransient and skips the item the owner claimed during the steal",
                   "[core][protocol]", fs::SeqCst, fs::Paper, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  Stage<TestType> s(6);
  s.owner().install(RangeList{{0, 6}});
  REQUIRE(s.claim() == 0u);
  REQUIRE(s.claim() == 1u);

  auto& owner = s.owner();
  auto& thief = s.thief();
  REQUIRE(thief.lock_victim(s.slot()));
  REQUIRE(thief.plan_share(s.slot()));  // T1, T2: Front = 2, End = 6, mid = 4: share [4, 6)
  CHECK(thief.planned_mid() == 4u);

  // The owner claims 2 and 3, then starts claiming 4 while the End it reads is still 6.
  REQUIRE(s.claim() == 2u);
  REQUIRE(s.claim() == 3u);
  owner.announce();                            // O1
  owner.storeload_fence();                     // F1
  const std::uint32_t end = owner.read_end();  // O2 reads 6: the thief has not shrunk yet
  CHECK(end == 6u);

  thief.shrink_victim(s.slot());                  // T3: End := 4
  thief.storeload_fence();                        // F2
  CHECK_FALSE(thief.victim_quiescent(s.slot()));  // T4 sees the claim in flight and must wait

  const auto claimed = owner.finish_claim(end);  // O3, O4: item 4 is the owner's
  REQUIRE(claimed == 4u);
  s.runs.record(*claimed);
  CHECK(thief.victim_quiescent(s.slot()));
  const std::uint32_t front_after = thief.reread_front(s.slot());  // T5 reads 5
  CHECK(front_after == 5u);
  thief.unlock_victim(s.slot());
  REQUIRE(thief.keep_unclaimed(front_after) == StealOutcome::kStolen);
  CHECK(thief.skipped() == 1u);
  CHECK(thief.share()[0] == IdRange{5, 6});

  s.install_share();
  s.drain(0);  // the owner now reads End = 4 and stops
  s.drain(1);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK(audit.exactly_once());
}

TEMPLATE_TEST_CASE("a thief that steals the last item while the owner claims it: one of them runs it",
                   "[core][protocol]", fs::SeqCst, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  Stage<TestType> s(2);
  s.owner().install(RangeList{{0, 2}});
  REQUIRE(s.claim() == 0u);
  auto& thief = s.thief();
  REQUIRE(thief.lock_victim(s.slot()));
  REQUIRE(thief.plan_share(s.slot()));  // one item left: mid = 1, the thief plans to take it
  s.owner().announce();
  s.owner().storeload_fence();
  const std::uint32_t end = s.owner().read_end();
  thief.shrink_victim(s.slot());
  thief.storeload_fence();
  CHECK_FALSE(thief.victim_quiescent(s.slot()));
  const auto claimed = s.owner().finish_claim(end);
  REQUIRE(claimed == 1u);
  s.runs.record(*claimed);
  const std::uint32_t front_after = thief.reread_front(s.slot());
  thief.unlock_victim(s.slot());
  CHECK(thief.keep_unclaimed(front_after) == StealOutcome::kSkippedAll);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK(audit.exactly_once());
}

// The store-buffering execution: the owner's O1 (ListTransient := 1) is still in its store buffer when it
// loads End (O2), so O2 reads the old End while the thief's T4 reads ListTransient = 0. Driven only where the
// policy's orders permit it.
TEMPLATE_TEST_CASE("store buffering at the handshake: Paper runs an item twice, fenced policies forbid it",
                   "[core][protocol][store-buffering]", fs::SeqCst, fs::Paper, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  constexpr bool permitted = !fs::forbids_store_buffering<TestType>();
  CHECK(permitted == (TestType::kContract == fs::Contract::kAtLeastOnce));
  if constexpr (permitted) {
    Stage<TestType> s(2);
    s.owner().install(RangeList{{0, 2}});
    REQUIRE(s.claim() == 0u);
    auto& owner = s.owner();
    auto& thief = s.thief();
    REQUIRE(thief.lock_victim(s.slot()));
    REQUIRE(thief.plan_share(s.slot()));
    const std::uint32_t end = owner.read_end();  // O2 executes while O1 is still buffered: reads End = 2
    thief.shrink_victim(s.slot());               // T3: End := 1
    thief.storeload_fence();                     // F2 (none under Paper)
    REQUIRE(thief.victim_quiescent(s.slot()));   // T4 reads ListTransient = 0: O1 not yet visible
    const std::uint32_t front_after = thief.reread_front(s.slot());  // T5 reads 1
    thief.unlock_victim(s.slot());
    REQUIRE(thief.keep_unclaimed(front_after) == StealOutcome::kStolen);  // keeps item 1
    owner.announce();                                                     // O1 drains from the store buffer
    const auto claimed = owner.finish_claim(end);                         // O3: claims item 1 too
    REQUIRE(claimed == 1u);
    s.runs.record(*claimed);
    s.install_share();
    s.drain(1);
    const auto audit = s.runs.audit_and_reset();
    INFO(audit);
    CHECK(audit.lost == 0u);        // at-least-once holds
    CHECK(audit.duplicated == 1u);  // exactly-once does not
    CHECK(audit.first_duplicated == std::vector<fs::ItemId>{1});
  } else {
    SUCCEED(TestType::kName << " orders O1 before O2 and T3 before T4: the execution is not permitted");
  }
}

TEMPLATE_TEST_CASE("negative controls: the exactly-once audit catches a broken protocol", "[core][protocol][negative]",
                   fs::BrokenSkipsReread, fs::BrokenNoTransient) {
  // The same sequentially consistent interleaving as the ListTransient test above: no weak memory needed.
  Stage<TestType> s(2);
  s.owner().install(RangeList{{0, 2}});
  REQUIRE(s.claim() == 0u);
  auto& thief = s.thief();
  REQUIRE(thief.lock_victim(s.slot()));
  REQUIRE(thief.plan_share(s.slot()));
  s.owner().announce();
  s.owner().storeload_fence();
  const std::uint32_t end = s.owner().read_end();
  thief.shrink_victim(s.slot());
  thief.storeload_fence();
  REQUIRE(thief.victim_quiescent(s.slot()));  // the defect: nothing to wait for
  const std::uint32_t front_after = thief.reread_front(s.slot());
  thief.unlock_victim(s.slot());
  REQUIRE(thief.keep_unclaimed(front_after) == StealOutcome::kStolen);
  const auto claimed = s.owner().finish_claim(end);
  REQUIRE(claimed == 1u);
  s.runs.record(*claimed);
  s.install_share();
  s.drain(1);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK_FALSE(audit.exactly_once());
  CHECK(audit.duplicated == 1u);
}

TEMPLATE_TEST_CASE("a batched claim takes up to n ids of one entry, bounded by End, in one handshake",
                   "[core][protocol][batch]", fs::SeqCst, fs::Paper, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  Stage<TestType> s(10);
  auto& owner = s.owner();
  owner.install(RangeList{{0, 3}, {5, 10}, {3, 5}});  // flat positions 0-2, 3-7, 8-9
  CHECK(owner.unclaimed_run() == IdRange{0, 3});
  CHECK(owner.try_claim_up_to(2) == IdRange{0, 2});
  CHECK(fs::Access<fs::StdBackend, TestType>::peek(s.slot().front) == 2u);  // O3 stored Front := 0 + 2
  CHECK(owner.try_claim_up_to(5) == IdRange{2, 3});                         // the entry bounds the batch
  CHECK(owner.unclaimed_run() == IdRange{5, 10});
  CHECK(owner.try_claim() == 5u);                   // single and batched claims mix
  CHECK(owner.try_claim_up_to(0) == std::nullopt);  // a batch of nothing claims nothing
  CHECK(owner.try_claim_up_to(100) == IdRange{6, 10});
  REQUIRE(s.thief().try_steal(s.slot()) == StealOutcome::kStolen);  // 2 left: the thief takes [4, 5)
  CHECK(s.thief().share()[0] == IdRange{4, 5});
  CHECK(owner.try_claim_up_to(100) == IdRange{3, 4});  // End = 9 bounds the batch, not the entry
  CHECK(owner.try_claim_up_to(100) == std::nullopt);
  CHECK(owner.claimed() == 9u);
}

// The batch analogue of the ListTransient test: the owner reads the old End at O2, the thief lowers End and
// must wait at T4; the batch's O3 then covers part of the planned share, and T5 drops it.
TEMPLATE_TEST_CASE("a thief skips the part of its share that a batched claim in flight took", "[core][protocol][batch]",
                   fs::SeqCst, fs::Fenced, fs::Asymmetric) {
  if (!policy_usable<TestType>()) return;
  Stage<TestType> s(8);
  auto& owner = s.owner();
  auto& thief = s.thief();
  owner.install(RangeList{{0, 8}});
  REQUIRE(thief.lock_victim(s.slot()));
  REQUIRE(thief.plan_share(s.slot()));  // Front = 0, End = 8: share [4, 8)
  REQUIRE(thief.planned_mid() == 4u);
  owner.announce();                            // O1
  owner.storeload_fence();                     // F1
  const std::uint32_t end = owner.read_end();  // O2 reads 8
  thief.shrink_victim(s.slot());               // T3: End := 4
  thief.storeload_fence();
  CHECK_FALSE(thief.victim_quiescent(s.slot()));  // the batch is in flight
  const auto claimed = owner.finish_claim_up_to(end, 6);
  REQUIRE(claimed == IdRange{0, 6});  // O3: Front := 6, legal by the End read at O2
  for (fs::ItemId id = claimed->begin; id < claimed->end; ++id) s.runs.record(id);
  REQUIRE(thief.victim_quiescent(s.slot()));
  const std::uint32_t front_after = thief.reread_front(s.slot());  // T5 reads 6
  thief.unlock_victim(s.slot());
  REQUIRE(thief.keep_unclaimed(front_after) == StealOutcome::kStolen);
  CHECK(thief.skipped() == 2u);
  CHECK(thief.share()[0] == IdRange{6, 8});
  s.install_share();
  CHECK(owner.try_claim_up_to(4) == std::nullopt);  // End = 4 < Front: the owner's list is done
  s.drain(1);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK(audit.exactly_once());
}

// The negative control: a batch bounded by its entry instead of End. After a completed steal the owner's next
// batch runs into the thief's share: no weak memory needed, the order is sequentially consistent.
TEMPLATE_TEST_CASE("negative control: a batch that ignores End runs stolen items twice", "[core][protocol][negative]",
                   fs::BrokenBatchIgnoresEnd, fs::Fenced) {
  Stage<TestType> s(8);
  s.owner().install(RangeList{{0, 8}});
  REQUIRE(s.thief().try_steal(s.slot()) == StealOutcome::kStolen);  // takes [4, 8), End := 4
  s.install_share();
  const auto claimed = s.owner().try_claim_up_to(6);
  REQUIRE(claimed);
  for (fs::ItemId id = claimed->begin; id < claimed->end; ++id) s.runs.record(id);
  s.drain(0);
  s.drain(1);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  if constexpr (fs::has(TestType::defects(), fs::Defect::kBatchIgnoresEnd)) {
    CHECK(audit.duplicated == 2u);  // ids 4 and 5
  } else {
    CHECK(audit.exactly_once());  // the same steps with the defect absent
  }
}

TEMPLATE_TEST_CASE("steal-from-a-thief chain: worker 2 steals from worker 1's stolen list", "[core][protocol]",
                   fs::SeqCst, fs::Fenced, fs::Paper) {
  Stage<TestType> s(16, 3);
  s.owner(0).install(RangeList{{0, 16}});
  s.owner(1).install(RangeList{});
  s.owner(2).install(RangeList{});
  REQUIRE(s.claim(0) == 0u);
  REQUIRE(s.thief(1).try_steal(s.slot(0)) == StealOutcome::kStolen);  // 15 left: takes [8, 16)
  CHECK(s.thief(1).share()[0] == IdRange{8, 16});
  s.install_share(1);
  REQUIRE(s.claim(1) == 8u);
  REQUIRE(s.thief(2).try_steal(s.slot(1)) == StealOutcome::kStolen);  // 7 left of [9, 16): takes [12, 16)
  CHECK(s.thief(2).share()[0] == IdRange{12, 16});
  s.install_share(2);
  s.drain(0);
  s.drain(1);
  s.drain(2);
  CHECK(s.thief(1).try_steal(s.slot(0)) == StealOutcome::kEmpty);
  const auto audit = s.runs.audit_and_reset();
  INFO(audit);
  CHECK(audit.exactly_once());
}

TEST_CASE("a busy LockList makes the next thief move on", "[core][protocol]") {
  Stage<fs::Fenced> s(8, 3);
  s.owner(0).install(RangeList{{0, 8}});
  REQUIRE(s.thief(1).lock_victim(s.slot(0)));
  CHECK(s.thief(2).try_steal(s.slot(0)) == StealOutcome::kLockBusy);
  s.thief(1).unlock_victim(s.slot(0));
  CHECK(s.thief(2).try_steal(s.slot(0)) == StealOutcome::kStolen);
}
