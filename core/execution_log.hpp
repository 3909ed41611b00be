// execution_log.hpp — who ran which item, one plain log per worker: the exactly-once audit of a measured frame,
// without a shared write or a locked instruction per item.
//
// Why not ExecutionCounter (execution_counter.hpp): its relaxed fetch_add per item is a locked instruction, and on
// x86 a locked instruction waits until every earlier store has left the store buffer. After an item that wrote
// its triangles that drain costs ~25-35 ns here, as much as a StoreLoad fence: measured in the main job's loss
// account, the audit's fetch_add cost queue-mutex 2.5-3.9 % of its frame while stealing/Fenced, whose claim
// fence had drained the buffer already, paid 0.4-0.6 % for it. An audit that charges one scheduler what it
// forgives another is not neutral. Here worker w appends the id to its own log (a plain store into memory no
// other thread touches during the frame), and the counting happens after the frame, outside every timed region.
//
// OWNERSHIP: log w is written by the one thread that runs as worker w during a frame (every scheduler runs each
// worker id on one thread at a time) and read by the caller after the frame, whose end orders the writes before
// the read. A worker that logs more ids than there are items (only when items run twice) keeps the excess as a
// count, which the audit reports as duplicated runs.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/execution_counter.hpp"
#include "core/id_range.hpp"

namespace frontsteal {

class ExecutionLog {
 public:
  ExecutionLog(ItemId items, WorkerId workers) : items_(items), counts_(items, 0) {
    for (WorkerId w = 0; w < std::max<WorkerId>(workers, 1); ++w) logs_.push_back(std::make_unique<Log>(items));
  }

  // Worker w ran `item` (w below the constructor's worker count).
  void record(ItemId item, WorkerId w) noexcept {
    Log& l = *logs_[w];
    if (l.size < l.ids.size()) {
      l.ids[l.size++] = item;
    } else {
      ++l.overflow;
    }
  }

  // The audit of everything logged since the last call (the ExecutionCounter's rules); the logs start empty.
  ExecutionAudit audit_and_reset() {
    std::fill(counts_.begin(), counts_.end(), 0u);
    std::uint64_t overflow = 0;
    for (auto& l : logs_) {
      for (std::size_t i = 0; i < l->size; ++i) ++counts_[l->ids[i]];
      overflow += l->overflow;
      l->size = 0;
      l->overflow = 0;
    }
    ExecutionAudit a;
    a.items = items_;
    for (ItemId i = 0; i < items_; ++i) a.classify(i, counts_[i]);
    if (overflow > 0) {  // more runs than items on one worker: some item ran twice, which one is not known
      a.extra_runs += overflow;
      if (a.duplicated == 0) a.duplicated = 1;
    }
    return a;
  }

 private:
  struct alignas(64) Log {
    explicit Log(ItemId items) : ids(items) {}
    std::vector<ItemId> ids;
    std::size_t size = 0;
    std::uint64_t overflow = 0;
  };
  ItemId items_;
  std::vector<std::unique_ptr<Log>> logs_;
  std::vector<std::uint32_t> counts_;
};

}  // namespace frontsteal
