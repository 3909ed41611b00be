// exactly_once_audit.hpp — every model's check of a simulated frame: each item ran exactly once.
//
// The same property the real schedulers are audited for (schedulers/, stress/), here on the model's own
// record of which worker ran what. Each model has a negative control that plants a lost update (a steal that
// never lowers the victim's End, a thief that skips the re-read of Front) and must be caught by this audit.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/id_range.hpp"

namespace frontsteal::simulation {

struct AuditFailure {
  ItemId item = 0;
  std::uint32_t runs = 0;  // how often it ran: 0 lost, 2 or more duplicated
  std::string what() const { return "item " + std::to_string(item) + " executed " + std::to_string(runs) + " times"; }
};

class ExactlyOnceAudit {
 public:
  explicit ExactlyOnceAudit(ItemId items) : runs_(items, 0) {}

  // Starts a frame: no item has run.
  void clear() { runs_.assign(runs_.size(), 0); }
  // One worker's record of the items it ran.
  void count(const std::vector<ItemId>& ran) {
    for (ItemId id : ran) ++runs_[id];
  }
  // The lowest item that did not run exactly once, if any.
  std::optional<AuditFailure> first_failure() const {
    for (std::size_t id = 0; id < runs_.size(); ++id) {
      if (runs_[id] != 1) return AuditFailure{static_cast<ItemId>(id), runs_[id]};
    }
    return std::nullopt;
  }

 private:
  std::vector<std::uint32_t> runs_;
};

}  // namespace frontsteal::simulation
