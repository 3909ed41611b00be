// team_scheduler.hpp — the part every scheduler that owns a WorkerTeam (worker_team.hpp) shares, written once:
// the per-worker slots, the frame's item function, run_frame (prepare, clear the slots, run the team,
// collect) and worker_count. A scheduler derives from TeamScheduler<Itself> (CRTP, so the per-worker loop is
// a direct call, not a second indirection per frame) and supplies
//   void work(WorkerId w);   the per-worker loop of one frame (runs on worker w, between T2 and T3)
//   void begin_frame();      optional: resets the scheduler's shared per-frame state (a cursor, a count);
//                            runs on the caller before the team's release (T1), which publishes it
// and reads slot(w) and process() from work().
//
// The team's threads start in this base's constructor, before the derived scheduler's members exist. They
// touch nothing of the derived class until the first frame is released (T1 -> T2 in worker_team.hpp), which
// only run_frame does, after construction; on destruction they are asleep between frames, and ~WorkerTeam
// stops them without running work() again. So constructing the team first is as safe as constructing it last.
#pragma once

#include <cstdint>
#include <vector>

#include "schedulers/scheduler.hpp"
#include "schedulers/worker_team.hpp"

namespace frontsteal::sched {

template <class Derived>
class TeamScheduler : public Scheduler {
 public:
  const FrameStats& run_frame(ItemFunctionRef process) final {
    process_ = &process;
    derived().begin_frame();  // published to the workers by the team's release (T1)
    for (auto& s : slots_) s.begin_frame();
    const FrameWindow window = team_.run_frame();
    return collect(stats_, slots_, window, &team_.spans());
  }
  WorkerId worker_count() const noexcept final { return team_.size(); }

 protected:
  explicit TeamScheduler(WorkerId workers)
      : slots_(workers), team_(workers, [this](WorkerId w) { derived().work(w); }) {}

  // Default: no shared per-frame state (static allocation).
  void begin_frame() {}
  // Worker w's slot: written by worker w during a frame only (worker_team.hpp, OWNERSHIP).
  WorkerSlot& slot(WorkerId w) noexcept { return slots_[w]; }
  // The frame's item function (valid during a frame).
  const ItemFunctionRef& process() const noexcept { return *process_; }

 private:
  Derived& derived() noexcept { return static_cast<Derived&>(*this); }

  std::vector<WorkerSlot> slots_;
  const ItemFunctionRef* process_ = nullptr;
  FrameStats stats_;
  WorkerTeam team_;
};

}  // namespace frontsteal::sched
