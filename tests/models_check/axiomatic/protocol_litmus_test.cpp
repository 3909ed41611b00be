// The handshake litmus (models_check/axiomatic/protocol_litmus.hpp) under the axiomatic checker: every
// exactly-once policy forbids the duplicate under RC11, RC11 without no-thin-air and ARMv8 (both acquire
// mappings); Paper's duplicate is allowed where the literature says; and each one-step weakening of Minimal's
// fences is killed (the duplicate becomes reachable), so the verdicts above are not vacuous; then the other paths
// (termination, the re-read, publication, the lock, reclamation, Chase–Lev take, push and last element) likewise.
#include "models_check/axiomatic/protocol_litmus.hpp"

#include <catch2/catch.hpp>

#include "models_check/axiomatic/checker.hpp"
#include "models_check/axiomatic/litmus_certificate.hpp"
#include "models_check/minimal_survivors.hpp"

namespace ax = frontsteal::axiomatic;
using frontsteal::Fence;
using frontsteal::Site;

namespace {

struct Duplicates {
  bool rc11, rc11_lb, armv8, armv8_ldapr;
};

Duplicates duplicates(const ax::LitmusTest& t) {
  return {ax::check(t, ax::Model::rc11).allowed, ax::check(t, ax::Model::rc11_without_nta).allowed,
          ax::check(ax::compile_to_armv8(t), ax::Model::armv8).allowed,
          ax::check(ax::compile_to_armv8(t, true, true), ax::Model::armv8).allowed};
}

// The bad outcome is unreachable under every model.
void check_forbidden_everywhere(const Duplicates& d) {
  CHECK_FALSE(d.rc11);
  CHECK_FALSE(d.rc11_lb);
  CHECK_FALSE(d.armv8);
  CHECK_FALSE(d.armv8_ldapr);
}

// Minimal with the fence at `Weak` replaced by `To`.
template <Site Weak, Fence To>
struct MinimalWeakened : frontsteal::Minimal {
  static constexpr std::string_view kName = "Minimal, one fence weakened";
  static constexpr Fence fence(Site s) noexcept { return s == Weak ? To : frontsteal::Minimal::fence(s); }
};

// `Base` with the order at `Weak` replaced by `To`.
template <class Base, Site Weak, frontsteal::Mo To>
struct OrderWeakened : Base {
  static constexpr frontsteal::Mo order(Site s) noexcept { return s == Weak ? To : Base::order(s); }
};
template <Site Weak, frontsteal::Mo To>
using MinimalOrderWeakened = OrderWeakened<frontsteal::Minimal, Weak, To>;
template <Site Weak, frontsteal::Mo To>
using PublicationWeakened = OrderWeakened<frontsteal::PublicationOrders, Weak, To>;
template <Site Weak, frontsteal::Mo To>
using ChaseLevWeakened = OrderWeakened<frontsteal::ChaseLevOrders, Weak, To>;

}  // namespace

TEST_CASE("exactly-once policies forbid the handshake's duplicate under every model", "[axiomatic]") {
  for (const ax::ProtocolLitmus& p : ax::handshake_litmus_all()) {
    if (p.contract != frontsteal::Contract::kExactlyOnce) continue;
    const Duplicates d = duplicates(p.test);
    INFO(p.policy);
    check_forbidden_everywhere(d);
  }
}

TEST_CASE("Paper's handshake: duplicate under C++ and with LDAPR, not with LDAR (STLR then LDAR is ordered)",
          "[axiomatic]") {
  const Duplicates d = duplicates(ax::handshake_litmus<frontsteal::Paper>().test);
  CHECK(d.rc11);
  CHECK(d.rc11_lb);
  CHECK_FALSE(d.armv8);
  CHECK(d.armv8_ldapr);
}

TEST_CASE("every one-step weakening of Minimal's handshake fences is killed", "[axiomatic]") {
  // Dropping either fence: the duplicate under C++. On ARMv8 the owner's always (O1 is a plain STR before O2's
  // LDAR); the thief's only with LDAPR: T3's release is an STLR, and STLR before T4's LDAR is ordered, as for Paper.
  const Duplicates owner =
      duplicates(ax::handshake_litmus<MinimalWeakened<Site::kOwnerStoreLoadFence, Fence::kNone>>().test);
  CHECK(owner.rc11);
  CHECK(owner.armv8);
  CHECK(owner.armv8_ldapr);
  const Duplicates thief =
      duplicates(ax::handshake_litmus<MinimalWeakened<Site::kThiefStoreLoadFence, Fence::kNone>>().test);
  CHECK(thief.rc11);
  CHECK_FALSE(thief.armv8);
  CHECK(thief.armv8_ldapr);
  // seq_cst → acq_rel: the duplicate under C++ (an acq_rel fence does not order a store before a load); not on
  // ARMv8, where the mapping makes every non-acquire fence a full DMB ISH.
  for (const Duplicates d :
       {duplicates(ax::handshake_litmus<MinimalWeakened<Site::kOwnerStoreLoadFence, Fence::kAcqRel>>().test),
        duplicates(ax::handshake_litmus<MinimalWeakened<Site::kThiefStoreLoadFence, Fence::kAcqRel>>().test)}) {
    CHECK(d.rc11);
    CHECK_FALSE(d.armv8);
  }
}

TEST_CASE("the handshake litmus carries the site table's labels", "[axiomatic]") {
  const ax::LitmusTest t = ax::handshake_litmus<frontsteal::Fenced>().test;
  REQUIRE(t.threads.size() == 2);
  CHECK(t.threads[0].front().label == frontsteal::info(Site::kOwnerAnnounce).label);
  CHECK(t.threads[0].back().label == frontsteal::info(Site::kOwnerReadEnd).label);
  CHECK(t.threads[1].front().label == frontsteal::info(Site::kThiefShrinkEnd).label);
  CHECK(t.threads[1].back().label == frontsteal::info(Site::kThiefAwaitTransient).label);
}

TEST_CASE("termination: Minimal as Relacy derives it lets an idle worker quit early under C++ with LB and on ARMv8",
          "[axiomatic]") {
  for (const ax::ProtocolLitmus& p : ax::termination_litmus_all()) {
    const Duplicates early_quit = duplicates(p.test);  // the same four models, the bad outcome is the early quit
    INFO(p.policy);
    if (p.policy == ax::MinimalRelacyDerived::kName) {
      CHECK_FALSE(early_quit.rc11);  // no-thin-air forbids it: the victim's leave is read by the thief's join
      CHECK(early_quit.rc11_lb);
      CHECK(early_quit.armv8);
      CHECK(early_quit.armv8_ldapr);
    } else {
      check_forbidden_everywhere(early_quit);
    }
  }
}

TEST_CASE(
    "termination: both of Minimal's orders T3 release and O2 acquire are needed under C++, on ARMv8 T3's "
    "release suffices",
    "[axiomatic]") {
  const Duplicates without_release =
      duplicates(ax::termination_litmus<MinimalOrderWeakened<Site::kThiefShrinkEnd, frontsteal::Mo::kRelaxed>>().test);
  CHECK(without_release.rc11_lb);
  CHECK(without_release.armv8);
  // O2 relaxed again: C++ keeps no dependency, so the early quit returns; ARMv8 orders O2 before A2's write by
  // the branch (ctrl;[W]) and T3's STLR orders A1 before T3.
  const Duplicates without_acquire =
      duplicates(ax::termination_litmus<MinimalOrderWeakened<Site::kOwnerReadEnd, frontsteal::Mo::kRelaxed>>().test);
  CHECK(without_acquire.rc11_lb);
  CHECK_FALSE(without_acquire.armv8);
}

TEST_CASE("publication: no torn component under any model, W1, W2 and P2 each needed", "[axiomatic]") {
  using frontsteal::Mo;
  const Duplicates sound = duplicates(ax::publication_litmus<frontsteal::PublicationOrders>().test);
  check_forbidden_everywhere(sound);
  // W1 without its acquire: the last tessellator does not acquire A's triangles (C++; on ARMv8 the branch on the
  // count-down and the exchange's release keep them ordered, so only C++ shows it).
  CHECK(duplicates(ax::publication_litmus<PublicationWeakened<Site::kWriterCountDown, Mo::kRelease>>().test).rc11);
  // W1 without its release: A's triangles are not released to the count-down.
  const Duplicates w1_acquire =
      duplicates(ax::publication_litmus<PublicationWeakened<Site::kWriterCountDown, Mo::kAcquire>>().test);
  CHECK(w1_acquire.rc11);
  CHECK(w1_acquire.armv8);
  // W2 relaxed: nothing released to the pusher under C++. On ARMv8 the last tessellator's LDADDAL is an acquire
  // (A), which orders every later access of its thread, the exchange included: there W2's release is redundant.
  const Duplicates w2 =
      duplicates(ax::publication_litmus<PublicationWeakened<Site::kWriterPublish, Mo::kRelaxed>>().test);
  CHECK(w2.rc11);
  CHECK_FALSE(w2.armv8);
  // P2 relaxed: the pusher's triangle read may come first.
  const Duplicates p2 =
      duplicates(ax::publication_litmus<PublicationWeakened<Site::kPusherReadPublished, Mo::kRelaxed>>().test);
  CHECK(p2.rc11);
  CHECK(p2.armv8);
}

TEST_CASE("the lock passes End from thief to thief under every policy, L2 acquire and L3 release each needed",
          "[axiomatic]") {
  using frontsteal::Mo;
  for (const ax::ProtocolLitmus& p : ax::lock_litmus_all()) {
    const Duplicates d = duplicates(p.test);
    INFO(p.policy);
    check_forbidden_everywhere(d);
  }
  for (const Duplicates d :
       {duplicates(ax::lock_litmus<MinimalOrderWeakened<Site::kLockAcquire, Mo::kRelaxed>>().test),
        duplicates(ax::lock_litmus<MinimalOrderWeakened<Site::kLockRelease, Mo::kRelaxed>>().test)}) {
    CHECK(d.rc11);
    CHECK(d.armv8);
  }
}

TEST_CASE("the re-read after the wait: no duplicate for exactly-once policies, O4 release and T4 acquire each needed",
          "[axiomatic]") {
  using frontsteal::Mo;
  for (const ax::ProtocolLitmus& p : ax::reread_litmus_all()) {
    if (p.contract != frontsteal::Contract::kExactlyOnce) continue;
    INFO(p.policy);
    check_forbidden_everywhere(duplicates(p.test));
  }
  // Without O4's release the claim (O3) and the retraction (O4) may reorder; without T4's acquire the re-read
  // (T5) may be satisfied before the wait ends: either way the thief keeps the item the owner claimed.
  for (const Duplicates d :
       {duplicates(ax::reread_litmus<MinimalOrderWeakened<Site::kOwnerRetract, Mo::kRelaxed>>().test),
        duplicates(ax::reread_litmus<MinimalOrderWeakened<Site::kThiefAwaitTransient, Mo::kRelaxed>>().test)}) {
    CHECK(d.rc11);
    CHECK(d.rc11_lb);
    CHECK(d.armv8);
    CHECK(d.armv8_ldapr);
  }
}

TEST_CASE("reclamation: no use after reuse, each of W2, W3, P1, P2 below seq_cst lets it happen", "[axiomatic]") {
  using frontsteal::Mo;
  const Duplicates sound = duplicates(ax::reclamation_litmus<frontsteal::PublicationOrders>().test);
  check_forbidden_everywhere(sound);
  // Under C++ each store→load pair needs seq_cst; on ARMv8 STLR/SWPAL then LDAR is ordered anyway, but LDAPR
  // (the RCpc mapping of an acquire load) is not.
  const Duplicates w3 =
      duplicates(ax::reclamation_litmus<PublicationWeakened<Site::kWriterReadStarted, Mo::kAcquire>>().test);
  CHECK(w3.rc11);
  CHECK(w3.armv8_ldapr);
  const Duplicates p2 =
      duplicates(ax::reclamation_litmus<PublicationWeakened<Site::kPusherReadPublished, Mo::kAcquire>>().test);
  CHECK(p2.rc11);
  CHECK(p2.armv8_ldapr);
  CHECK(duplicates(ax::reclamation_litmus<PublicationWeakened<Site::kWriterPublish, Mo::kAcqRel>>().test).rc11);
  CHECK(duplicates(ax::reclamation_litmus<PublicationWeakened<Site::kPusherAnnounce, Mo::kRelease>>().test).rc11);
}

TEST_CASE("Chase-Lev: take against two steals returns no element twice, without K3 it does", "[axiomatic]") {
  const Duplicates sound = duplicates(ax::chase_lev_litmus<frontsteal::ChaseLevOrders>().test);
  check_forbidden_everywhere(sound);
  const Duplicates broken = duplicates(ax::chase_lev_litmus<frontsteal::BrokenTakeWithoutFence>().test);
  CHECK(broken.rc11);
  CHECK(broken.armv8);
}

TEST_CASE("Chase-Lev push: no steal of an unwritten element, B4 and S3's acquire each needed", "[axiomatic]") {
  using frontsteal::Mo;
  check_forbidden_everywhere(duplicates(ax::chase_lev_push_litmus<frontsteal::ChaseLevOrders>().test));
  for (const Duplicates d :
       {duplicates(ax::chase_lev_push_litmus<frontsteal::BrokenPushWithoutRelease>().test),
        duplicates(ax::chase_lev_push_litmus<ChaseLevWeakened<Site::kStealReadBottom, Mo::kRelaxed>>().test)}) {
    CHECK(d.rc11);
    CHECK(d.rc11_lb);
    CHECK(d.armv8);  // a branch orders no later load on ARMv8 (ctrl;[W] only)
    CHECK(d.armv8_ldapr);
  }
}

TEST_CASE("Chase-Lev's last element: the two CASes let one side win, without K6 both take it", "[axiomatic]") {
  check_forbidden_everywhere(duplicates(ax::chase_lev_last_litmus<frontsteal::ChaseLevOrders>().test));
  const Duplicates broken = duplicates(ax::chase_lev_last_litmus<frontsteal::BrokenTakeLastWithoutCas>().test);
  CHECK(broken.rc11);
  CHECK(broken.rc11_lb);
  CHECK(broken.armv8);
  CHECK(broken.armv8_ldapr);
}

TEST_CASE(
    "core's Minimal is certified on the stealing paths: every one-step weakening they reach is killed under C++ "
    "with load buffering",
    "[axiomatic]") {
  const ax::LitmusCertificate c = ax::certify_on_stealing_paths(frontsteal::model::table_of<frontsteal::Minimal>());
  CHECK(c.base_failures.empty());
  int reached = 0;
  for (const ax::WeakeningRow& r : c.rows) {
    INFO(r.site << " " << r.from << " -> " << r.to);
    if (r.paths.empty()) continue;
    ++reached;
    CHECK(r.killed_under_cpp);
  }
  CHECK(reached >= 8);  // F1, F2, O2, O4, T3, T4, L2, L3
  CHECK(c.certified());
}

TEST_CASE(
    "Relacy's listed survivors of Minimal are exactly the weakenings the axiomatic checker kills that Relacy "
    "cannot: each one is killed here under C++ with load buffering, on its listed path",
    "[axiomatic]") {
  const ax::LitmusCertificate c = ax::certify_on_stealing_paths(frontsteal::model::table_of<frontsteal::Minimal>());
  REQUIRE(frontsteal::model::minimal_survivors().size() == 2);
  for (const frontsteal::model::NeededBeyondRelacy& listed : frontsteal::model::minimal_survivors()) {
    INFO(frontsteal::info(listed.site).label);
    CHECK(frontsteal::Minimal::order(listed.site) == listed.order);
    bool found = false;
    for (const ax::WeakeningRow& r : c.rows) {
      if (r.site != frontsteal::info(listed.site).label) continue;
      found = true;
      CHECK(r.killed_under_cpp);
      bool on_path = false;
      for (const std::string& kill : r.kills) on_path = on_path || kill.rfind(std::string(listed.path) + ":", 0) == 0;
      CHECK(on_path);
    }
    CHECK(found);
  }
}

TEST_CASE(
    "control: the certificate rejects Minimal as Relacy derives it (early quit) and finds SeqCst's redundant "
    "orders",
    "[axiomatic][negative-control]") {
  const ax::LitmusCertificate minimal =
      ax::certify_on_stealing_paths(frontsteal::model::table_of<ax::MinimalRelacyDerived>());
  CHECK_FALSE(minimal.base_failures.empty());
  CHECK_FALSE(minimal.certified());
  // SeqCst's handshake accesses are seq_cst and its F1/F2 fences too: one step off any one of them is covered by
  // the rest, so some weakening it reaches survives, and the certificate must say so.
  const ax::LitmusCertificate seq_cst =
      ax::certify_on_stealing_paths(frontsteal::model::table_of<frontsteal::SeqCst>());
  CHECK(seq_cst.base_failures.empty());
  CHECK_FALSE(seq_cst.certified());
}
