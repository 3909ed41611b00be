// table_policy.hpp — a memory-order policy read from a run-time table, so one checker binary runs every
// policy and every mutant (Relacy takes orders as run-time arguments; a compile-time policy per mutant would
// cost ~5 s and 265 MB of compilation each).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/memory_order.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "core/site.hpp"

namespace frontsteal::model {

struct PolicyTable {
  std::string name;
  Contract contract = Contract::kExactlyOnce;
  Defect defects = Defect::kNone;
  std::array<Mo, kSiteCount> orders{};
  std::array<Fence, kSiteCount> fences{};

  Mo& order(Site s) { return orders[static_cast<std::size_t>(s)]; }
  Fence& fence(Site s) { return fences[static_cast<std::size_t>(s)]; }
};

// The table of a compile-time policy.
template <class Policy>
PolicyTable table_of() {
  PolicyTable t;
  t.name = std::string(Policy::kName);
  t.contract = Policy::kContract;
  t.defects = Policy::defects();
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    const Site s = static_cast<Site>(i);
    if (info(s).kind == SiteKind::kFence) {
      t.fences[i] = Policy::fence(s);
      t.orders[i] = Mo::kRelaxed;
    } else {
      t.orders[i] = Policy::order(s);
      t.fences[i] = Fence::kNone;
    }
  }
  return t;
}

// The table every TablePolicy access reads. Set before each rl::simulate; constant during it.
inline PolicyTable& current_table() {
  static PolicyTable table;
  return table;
}

struct TablePolicy {
  static constexpr std::string_view kName = "table";
  // At-least-once as far as the frame loop is concerned: it always rebuilds a partition at the frame end, so a
  // mutant's duplicate in frame 1 does not cascade into frame 2. The contract that is *checked* is the
  // table's (see protocol_suite.hpp).
  static constexpr Contract kContract = Contract::kAtLeastOnce;
  static constexpr bool kNeedsMembarrier = false;
  static Mo order(Site s) noexcept { return current_table().orders[static_cast<std::size_t>(s)]; }
  static Fence fence(Site s) noexcept { return current_table().fences[static_cast<std::size_t>(s)]; }
  static Defect defects() noexcept { return current_table().defects; }
};

// The stealing protocol's policies and negative controls, as tables: what every checker of core/ runs.
inline std::vector<PolicyTable> known_stealing_policies() {
  return {table_of<SeqCst>(),
          table_of<Paper>(),
          table_of<Fenced>(),
          table_of<Asymmetric>(),
          table_of<Minimal>(),
          table_of<BrokenSkipsReread>(),
          table_of<BrokenNoTransient>(),
          table_of<BrokenJoinsLate>(),
          table_of<BrokenShareLowerBound>(),
          table_of<BrokenBatchIgnoresEnd>()};
}

// One-step weakenings, weakest last: loads seq_cst > acquire > relaxed; stores seq_cst > release > relaxed;
// read-modify-writes seq_cst > acq_rel > {acquire, release} > relaxed; fences seq_cst > acq_rel >
// {acquire, release} > none, and an asymmetric or compiler fence > none.
inline std::vector<Mo> weaker_orders(Mo m, SiteKind kind) {
  switch (kind) {
    case SiteKind::kLoad:
      if (m == Mo::kSeqCst) return {Mo::kAcquire};
      if (m == Mo::kAcquire) return {Mo::kRelaxed};
      return {};
    case SiteKind::kStore:
      if (m == Mo::kSeqCst) return {Mo::kRelease};
      if (m == Mo::kRelease) return {Mo::kRelaxed};
      return {};
    case SiteKind::kReadModifyWrite:
      if (m == Mo::kSeqCst) return {Mo::kAcqRel};
      if (m == Mo::kAcqRel) return {Mo::kAcquire, Mo::kRelease};
      if (m == Mo::kAcquire || m == Mo::kRelease) return {Mo::kRelaxed};
      return {};
    case SiteKind::kFence: return {};
  }
  return {};
}

inline std::vector<Fence> weaker_fences(Fence f) {
  switch (f) {
    case Fence::kSeqCst: return {Fence::kAcqRel};
    case Fence::kAcqRel: return {Fence::kAcquire, Fence::kRelease};
    case Fence::kAcquire:
    case Fence::kRelease:
    case Fence::kCompiler:
    case Fence::kAsymmetricLight:
    case Fence::kAsymmetricHeavy: return {Fence::kNone};
    case Fence::kNone: return {};
  }
  return {};
}

struct Mutant {
  Site site;
  std::string from;
  std::string to;
  PolicyTable table;
};

// Every one-step weakening of every site of `base` that belongs to `protocol`.
inline std::vector<Mutant> one_step_mutants(const PolicyTable& base, Protocol protocol = Protocol::kStealing) {
  std::vector<Mutant> out;
  for (std::size_t i = 0; i < kSiteCount; ++i) {
    const Site s = static_cast<Site>(i);
    if (info(s).protocol != protocol) continue;
    if (info(s).kind == SiteKind::kFence) {
      for (Fence f : weaker_fences(base.fences[i])) {
        Mutant m{s, std::string(name(base.fences[i])), std::string(name(f)), base};
        m.table.fences[i] = f;
        m.table.name = base.name + "[" + std::string(info(s).label) + ":" + m.to + "]";
        out.push_back(std::move(m));
      }
    } else {
      for (Mo o : weaker_orders(base.orders[i], info(s).kind)) {
        Mutant m{s, std::string(name(base.orders[i])), std::string(name(o)), base};
        m.table.orders[i] = o;
        m.table.name = base.name + "[" + std::string(info(s).label) + ":" + m.to + "]";
        out.push_back(std::move(m));
      }
    }
  }
  return out;
}

}  // namespace frontsteal::model
