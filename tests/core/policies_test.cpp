// Memory-order policies (core/policies.hpp): contracts, site tables, and the static store-buffering reading.
#include "core/policies.hpp"

#include <catch2/catch.hpp>

#include "core/negative_controls.hpp"

namespace fs = frontsteal;

TEST_CASE("every site has a unique label and name", "[core][policy]") {
  for (std::size_t i = 0; i < fs::kSiteCount; ++i) {
    for (std::size_t j = i + 1; j < fs::kSiteCount; ++j) {
      CHECK(fs::kSiteTable[i].label != fs::kSiteTable[j].label);
      CHECK(fs::kSiteTable[i].name != fs::kSiteTable[j].name);
    }
  }
}

TEST_CASE("contracts follow the handshake's fences", "[core][policy]") {
  // A policy may claim exactly-once only if its orders forbid store buffering at the handshake.
  CHECK(fs::SeqCst::kContract == fs::Contract::kExactlyOnce);
  CHECK(fs::Fenced::kContract == fs::Contract::kExactlyOnce);
  CHECK(fs::Asymmetric::kContract == fs::Contract::kExactlyOnce);
  CHECK(fs::Paper::kContract == fs::Contract::kAtLeastOnce);
  STATIC_REQUIRE(fs::forbids_store_buffering<fs::SeqCst>());
  STATIC_REQUIRE(fs::forbids_store_buffering<fs::Fenced>());
  STATIC_REQUIRE(fs::forbids_store_buffering<fs::Asymmetric>());
  STATIC_REQUIRE_FALSE(fs::forbids_store_buffering<fs::Paper>());
}

namespace {
// Fenced with the thief's fence removed: one side alone does not forbid store buffering.
struct OwnerFenceOnly : fs::Fenced {
  static constexpr fs::Fence fence(fs::Site s) noexcept {
    return s == fs::Site::kOwnerStoreLoadFence ? fs::Fence::kSeqCst : fs::Fence::kNone;
  }
};
// The asymmetric light side without the heavy side is not a fence at all.
struct LightOnly : fs::Fenced {
  static constexpr fs::Fence fence(fs::Site s) noexcept {
    return s == fs::Site::kOwnerStoreLoadFence ? fs::Fence::kAsymmetricLight : fs::Fence::kSeqCst;
  }
};
}  // namespace

TEST_CASE("the static store-buffering reading rejects half-fenced policies", "[core][policy]") {
  STATIC_REQUIRE_FALSE(fs::forbids_store_buffering<OwnerFenceOnly>());
  // A seq_cst fence on the thief and only a compiler barrier on the owner: the owner's store can still sit
  // in its store buffer while it loads End.
  STATIC_REQUIRE_FALSE(fs::forbids_store_buffering<LightOnly>());
}

TEST_CASE("every planted defect is one bit of its own and names the primitive it breaks", "[core][policy]") {
  std::uint32_t all = 0;
  for (const fs::DefectInfo& row : fs::kDefectTable) {
    const auto bit = static_cast<std::uint32_t>(row.defect);
    CHECK((all & bit) == 0);
    all |= bit;
    CHECK(fs::has(row.defect, row.defect));
    CHECK_FALSE(fs::has(fs::Defect::kNone, row.defect));
  }
  // Room for the next negative control: the type is wider than the bits in use.
  CHECK(all < (std::uint32_t{1} << 31));
  // The stealing protocol's negative controls plant stealing defects; the others belong to their primitives.
  CHECK(fs::protocol_of(fs::BrokenSkipsReread::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::BrokenNoTransient::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::BrokenJoinsLate::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::BrokenShareLowerBound::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::BrokenNeverRetracts::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::BrokenBatchIgnoresEnd::defects()) == fs::Protocol::kStealing);
  CHECK(fs::protocol_of(fs::Defect::kReuseWithoutGrace) == fs::Protocol::kPublication);
  CHECK(fs::protocol_of(fs::Defect::kPublishEachSurface) == fs::Protocol::kPublication);
  CHECK(fs::protocol_of(fs::Defect::kTakeLastWithoutCas) == fs::Protocol::kChaseLev);
  const fs::Defect two = fs::Defect::kSkipFrontReread | fs::Defect::kOwnerNeverRetracts;
  CHECK(fs::has(two, fs::Defect::kOwnerNeverRetracts));
  CHECK_FALSE(fs::has(two, fs::Defect::kThiefJoinsLate));
}
