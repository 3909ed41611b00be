// stealing_program.hpp — a protocol scenario (models_check/scenarios.hpp) as a program for the explorer: the
// same scenarios, the same frame loop (core/frame_loop.hpp) and the same policy tables as the Relacy tier
// (protocol_suite.hpp), over the execution-graph backend.
//
// Checks on every complete execution: each item ran exactly once per frame (exactly-once mode) or at least once
// (at-least-once mode); under RC11 no data race on a plain cell (the list bodies, the hand-over cells, the
// payloads a run increments); no early quit: the active count never read 0 by an idle worker (A3) and then raised
// by a join (A1) in the same frame, which is the termination invariant I-T (active_workers.hpp) failing; and the
// frame loop's own invariants. A run that ends in a wait nothing can satisfy is a hang (explorer.hpp).
#pragma once

#include <memory>
#include <vector>

#include "core/frame_loop.hpp"
#include "core/phase_timer.hpp"
#include "models_check/graph/explorer.hpp"
#include "models_check/graph/graph_backend.hpp"
#include "models_check/scenarios.hpp"
#include "models_check/search.hpp"
#include "models_check/table_policy.hpp"

namespace frontsteal::graph {

class StealingProgram final : public Program {
 public:
  StealingProgram(const model::ScenarioSpec& spec, model::CheckMode mode) : spec_(spec), mode_(mode) {}

  int threads() const override { return static_cast<int>(spec_.threads()); }

  void setup() override {
    for (auto& frame : runs_) frame.fill(0);
    item_marks_.assign(spec_.threads(), {});
    core_ = std::make_unique<Workers>(spec_.workers, spec_.items, 1);
    core_->reseed(spec_.initial);
    core_->set_claim_batch(spec_.claim_batch);
    for (WorkerId w = 0; w < spec_.victims.size(); ++w) core_->set_victims(w, spec_.victims[w]);
    payload_.clear();
    frame_input_.clear();
    if (mode_ == model::CheckMode::kExactlyOnce) {
      for (ItemId i = 0; i < spec_.items; ++i) payload_.push_back(std::make_unique<GraphCell<int>>());
    }
    if (spec_.with_caller) {
      for (std::uint32_t k = 0; k < spec_.frames; ++k) frame_input_.push_back(std::make_unique<GraphCell<int>>());
    } else {
      core_->release_frame(spec_.frames);  // frames pre-released: no caller thread
    }
  }

  void run_thread(int index) override {
    if (spec_.with_caller && index == static_cast<int>(spec_.workers)) return caller();
    for (std::uint32_t k = 1; k <= spec_.frames; ++k) {
      core_->await_frame_start(k);
      auto process = [this, k, index](ItemId id, WorkerId) {
        worker_of_fiber_ = index;  // one fiber runs at a time
        run_item(id, k);
      };
      core_->run_frame(static_cast<WorkerId>(index), k, process);
    }
  }

  Outcome check(const Graph& g) override {
    for (std::uint32_t k = 1; k <= spec_.frames; ++k) {
      for (ItemId i = 0; i < spec_.items; ++i) {
        const int n = runs_[k - 1][i];
        if (n == 0) return {Verdict::kLost, "item " + std::to_string(i) + " never ran in frame " + std::to_string(k)};
        if (n > 1 && mode_ == model::CheckMode::kExactlyOnce) {
          return {Verdict::kDuplicate, "item " + std::to_string(i) + " ran twice in frame " + std::to_string(k)};
        }
      }
    }
    if (std::string quit = early_quit(g); !quit.empty()) return {Verdict::kEarlyQuit, quit};
    return {};
  }

  void teardown() override {
    core_.reset();
    payload_.clear();
    frame_input_.clear();
  }

 private:
  using Workers = StealingWorkers<GraphBackend, model::TablePolicy, NoPhaseTimer>;
  using A = frontsteal::Access<GraphBackend, model::TablePolicy>;

  void caller() {
    for (std::uint32_t k = 1; k <= spec_.frames; ++k) {
      A::write(*frame_input_[k - 1], static_cast<int>(k));
      core_->release_frame(k);
      core_->await_frame_done(k);
      for (WorkerId w = 0; w < spec_.workers; ++w) {  // as StealingScheduler does after every frame
        (void)core_->stats(w);
        (void)core_->failure(w);
      }
      for (std::size_t i = 0; i < payload_.size(); ++i) {
        if (A::read(*payload_[i]) != static_cast<int>(k)) {
          runtime::fail(Verdict::kLost, "caller: an item's payload is not up to date after the frame", __FILE__,
                        __LINE__);
        }
      }
    }
  }

  void run_item(ItemId id, std::uint32_t k) {
    if (spec_.with_caller && A::read(*frame_input_[k - 1]) != static_cast<int>(k)) {
      runtime::fail(Verdict::kOtherFailure, "worker read a stale frame input", __FILE__, __LINE__);
    }
    ++runs_[k - 1][id];
    item_marks_[static_cast<std::size_t>(worker_of_fiber_)].push_back(runtime::events_so_far());
    if (!payload_.empty()) A::write(*payload_[id], A::read(*payload_[id]) + 1);
  }

  // An idle worker read the active count 0 (A3) from a write that a join (A1) follows in coherence order, and the
  // joining thief then ran items of its share before it left again (A2): the count passed through 0 while
  // stealable work remained. (A join whose share turns out empty at the re-read is harmless.)
  std::string early_quit(const Graph& g) const {
    for (const GraphEvent& poll : g.events) {
      if (!poll.has_site || poll.site != Site::kActivePoll || poll.kind != ax::EventKind::read) continue;
      if (decode<std::uint32_t>(poll.value) != 0) continue;
      const auto& co = g.locations[static_cast<std::size_t>(poll.location)].co;
      const auto at = std::find(co.begin(), co.end(), poll.rf);
      if (at + 1 >= co.end()) continue;
      const int join = *(at + 1);
      const GraphEvent& next = g.events[join];
      if (!next.has_site || next.site != Site::kActiveJoin) continue;
      const auto& list = g.thread_events[static_cast<std::size_t>(next.thread)];
      const std::size_t joined = static_cast<std::size_t>(std::find(list.begin(), list.end(), join) - list.begin());
      std::size_t left = list.size();
      for (std::size_t i = joined + 1; i < list.size(); ++i) {
        if (g.events[list[i]].has_site && g.events[list[i]].site == Site::kActiveLeave) {
          left = i;
          break;
        }
      }
      for (std::size_t mark : item_marks_[static_cast<std::size_t>(next.thread)]) {
        if (mark > joined && mark <= left) {
          return "worker " + std::to_string(poll.thread) + " read the active count 0 and stopped looking; worker " +
                 std::to_string(next.thread) + " joined after it and ran items of its share";
        }
      }
    }
    return {};
  }

  const model::ScenarioSpec& spec_;
  model::CheckMode mode_;
  std::unique_ptr<Workers> core_;
  std::array<std::array<int, model::kMaxScenarioItems>, model::kMaxScenarioFrames> runs_{};
  std::vector<std::unique_ptr<GraphCell<int>>> payload_, frame_input_;
  std::vector<std::vector<std::size_t>> item_marks_;  // per thread: its event count when each item started
  int worker_of_fiber_ = 0;
};

}  // namespace frontsteal::graph
