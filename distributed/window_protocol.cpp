// window_protocol.cpp — WindowProtocol (window_protocol.hpp): core's Owner, Thief, ActivitySlot and ActiveWorkers
// over RmaBackend, one instantiation per F1 kind and policy.
#include "distributed/window_protocol.hpp"

#include <thread>
#include <vector>

#include "core/active_workers.hpp"
#include "core/activity_list.hpp"
#include "core/negative_controls.hpp"
#include "core/policies.hpp"
#include "distributed/rma_backend.hpp"

// The window backend skips the lock probe (V3); every other backend keeps it.
static_assert(!frontsteal::kProbesLock<frontsteal::mpi::RmaBackend<>>);
static_assert(frontsteal::kProbesLock<frontsteal::StdBackend>);

namespace frontsteal::mpi {
namespace {

using Clock = std::chrono::steady_clock;

// What core's Thief tells us during one attempt (core's StealObserver): the T4 wait's duration, and the
// forced overlap of the test hook at `planned`.
template <class Thief>
class WindowObserver {
 public:
  WindowObserver(const Thief& thief, RmaWindow& win, int victim, const StealHooks& hooks, double& waited_s)
      : thief_(thief), win_(win), victim_(victim), hooks_(hooks), waited_s_(waited_s) {}
  void locked() noexcept {}
  void planned() {
    if (!hooks_.force_overlap) return;
    const auto until = Clock::now() + hooks_.overlap_timeout;
    while (win_.get(victim_, kFront) <= thief_.planned_mid() && Clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  }
  void wait_begins() noexcept { wait_from_ = Clock::now(); }
  void wait_over() noexcept {
    if (wait_from_ != Clock::time_point{})
      waited_s_ += std::chrono::duration<double>(Clock::now() - wait_from_).count();
  }

 private:
  const Thief& thief_;
  RmaWindow& win_;
  int victim_;
  const StealHooks& hooks_;
  double& waited_s_;
  Clock::time_point wait_from_{};
};

template <OwnerFence F1, class Policy>
class CoreOverWindow final : public WindowProtocol {
 public:
  using Backend = RmaBackend<F1>;
  using Slot = ActivitySlot<Backend, Policy>;

  CoreOverWindow(RmaWindow& win, int ranks)
      : win_(win),
        fence_(win),
        active_(0u, RmaHome{&win, 0}),
        slots_(make_slots(win, ranks)),
        owner_(*slots_[static_cast<std::size_t>(win.rank())]),
        thief_(active_, win.capacity()) {}

  std::optional<ItemId> try_claim() override { return owner_.try_claim(); }
  std::optional<IdRange> try_claim_up_to(std::uint32_t n) override { return owner_.try_claim_up_to(n); }
  IdRange unclaimed_run() override { return owner_.unclaimed_run(); }
  void install(std::span<const IdRange> list) override { owner_.install(list); }
  std::uint32_t unclaimed() override {
    const std::uint32_t end = win_.local(kEnd).load(std::memory_order_acquire);
    return end > owner_.claimed() ? end - owner_.claimed() : 0;
  }
  StealOutcome try_steal(int victim, const StealHooks& hooks) override {
    const std::uint64_t polls_before = Backend::t4_polls();
    const std::uint64_t operations_before = win_.operations();
    WindowObserver<Thief<Backend, Policy>> observe(thief_, win_, victim, hooks, t4_wait_s_);
    const StealOutcome out = thief_.try_steal(*slots_[static_cast<std::size_t>(victim)], observe);
    t4_polls_ += Backend::t4_polls() - polls_before;
    if (out == StealOutcome::kStolen) stolen_operations_ += win_.operations() - operations_before;
    return out;
  }
  std::span<const IdRange> share() const override { return thief_.share(); }
  void leave() override { active_.leave(); }
  void join() override { active_.join(); }
  bool all_idle() override { return active_.all_idle(); }
  void rearm(std::uint32_t ranks) override { active_.rearm(ranks); }
  std::uint64_t stolen_operations() const override { return stolen_operations_; }
  double t4_wait_s() const override { return t4_wait_s_; }
  std::uint64_t t4_polls() const override { return t4_polls_; }
  std::string_view backend_name() const override { return Backend::kName; }
  std::string_view policy_name() const override { return Policy::kName; }

 private:
  static std::vector<std::unique_ptr<Slot>> make_slots(RmaWindow& win, int ranks) {
    std::vector<std::unique_ptr<Slot>> slots;
    for (int r = 0; r < ranks; ++r) slots.push_back(std::make_unique<Slot>(win.capacity(), RmaHome{&win, r}));
    return slots;
  }

  RmaWindow& win_;
  RmaFenceWindow<F1> fence_;
  ActiveWorkers<Backend, Policy> active_;
  std::vector<std::unique_ptr<Slot>> slots_;  // slots_[r]: rank r's part of the window
  Owner<Backend, Policy> owner_;
  Thief<Backend, Policy> thief_;
  double t4_wait_s_ = 0;
  std::uint64_t t4_polls_ = 0;
  std::uint64_t stolen_operations_ = 0;
};

template <OwnerFence F1>
std::unique_ptr<WindowProtocol> with_policy(RmaWindow& win, int ranks, WindowPolicy policy) {
  if (policy == WindowPolicy::kBrokenSkipsReread)
    return std::make_unique<CoreOverWindow<F1, BrokenSkipsReread>>(win, ranks);
  return std::make_unique<CoreOverWindow<F1, Fenced>>(win, ranks);
}

}  // namespace

void read_victims_in_views(bool on) noexcept {
  RmaBackend<OwnerFence::kCpu>::read_views() = on;
  RmaBackend<OwnerFence::kWinSync>::read_views() = on;
}

void plant_stale_view(bool on) noexcept {
  RmaBackend<OwnerFence::kCpu>::plant_stale_view() = on;
  RmaBackend<OwnerFence::kWinSync>::plant_stale_view() = on;
}

std::unique_ptr<WindowProtocol> make_window_protocol(RmaWindow& win, int ranks, bool win_sync_f1, WindowPolicy policy) {
  if (win_sync_f1) return with_policy<OwnerFence::kWinSync>(win, ranks, policy);
  return with_policy<OwnerFence::kCpu>(win, ranks, policy);
}

}  // namespace frontsteal::mpi
