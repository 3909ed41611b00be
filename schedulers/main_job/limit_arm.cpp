// limit_arm.cpp — P serial loops at once (limit_arm.hpp).
#include "schedulers/main_job/limit_arm.hpp"

#include <stdexcept>
#include <utility>

namespace frontsteal::main_job {

LimitCopies::LimitCopies(ts::PathScene& scene, WorkerId copies, bool reuse) {
  for (WorkerId w = 0; w < copies; ++w) {
    copies_.push_back(std::make_unique<ts::FrameWorkload>(scene, 1, ts::FrameWorkload::Buffers::kOwn));
    copies_.back()->set_reuse(reuse);
  }
}

void LimitCopies::grow(int f, ItemId id) {
  for (auto& c : copies_) c->run(f, id, 0);
}

void LimitCopies::prime(int first, WorkerId copies) {
  for (WorkerId w = 0; w < copies; ++w) copies_[w]->prime(first);
}

LimitArm::LimitArm(LimitCopies& pool, WorkerId p, std::function<void(WorkerId)> pin, measure::ItemSampler& sampler)
    : pool_((p <= pool.size() ? void() : throw std::invalid_argument("limit arm: fewer copies than workers"), pool)),
      p_(p),
      pin_(std::move(pin)),
      sampler_(sampler),
      team_(p, [this](WorkerId w) { copy_loop(w); }) {
  last_.copy_ns.assign(p, 0);
  last_.triangles.assign(p, 0);
  last_.inconsistent.assign(p, 0);
}

// Copy w's serial loop: the serial loop's own body (no per-item checks: nothing is shared), the sampled surfaces
// timed as in every other arm.
void LimitArm::copy_loop(WorkerId w) {
  pin_(w);
  ts::FrameWorkload& copy = pool_.copy(w);
  const int f = frame_;
  const auto start = sched::Clock::now();
  const ItemId n = copy.surfaces();
  for (ItemId id = 0; id < n; ++id) {
    sampler_.run(
        id, w, [] {}, [&] { copy.run(f, id, 0); });
  }
  last_.copy_ns[w] = sched::nanoseconds_since(start);
}

const LimitFrame& LimitArm::run_frame(int f) {
  frame_ = f;  // published to the copies by the team's release
  last_.window = team_.run_frame();
  for (WorkerId w = 0; w < p_; ++w) {
    last_.triangles[w] = pool_.copy(w).frame_triangles();
    last_.inconsistent[w] = pool_.copy(w).count_inconsistent();
  }
  return last_;
}

}  // namespace frontsteal::main_job
