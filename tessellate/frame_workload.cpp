// frame_workload.cpp — items of a frame and their totals (frame_workload.hpp).
#include "tessellate/frame_workload.hpp"

#include <algorithm>

namespace frontsteal::tess {

FrameWorkload::FrameWorkload(PathScene& scene, WorkerId workers, Buffers buffers)
    : scene_(&scene),
      own_(buffers == Buffers::kOwn ? scene.surfaces() : 0),
      scratch_(std::max<WorkerId>(1, workers)),
      triangles_(scene.surfaces(), 0),
      inconsistent_(scene.surfaces(), 0),
      capped_(scene.surfaces(), 0),
      remade_(scene.surfaces(), 0) {}

void FrameWorkload::prepare_workers(WorkerId workers) {
  if (scratch_.size() < workers) scratch_.resize(workers);
}

void FrameWorkload::set_reuse(bool on) {
  reuse_ = on;
  kept_.assign(on ? scene_->surfaces() : 0, KeptTessellation{});
}

void FrameWorkload::prime(int first) {
  if (!reuse_) return;
  if (first <= 0) {
    for (KeptTessellation& k : kept_) k.forget();
    return;
  }
  for (ItemId id = 0; id < surfaces(); ++id) run(first - 1, id, 0);
}

SurfaceResult FrameWorkload::run(int f, ItemId id, WorkerId w) {
  SurfaceResult r;
  if (reuse_) {
    const ReuseOutcome o = tessellate_or_reuse(scene_->prepared[id], scene_->cameras[f], scene_->frusta[f],
                                               scene_->settings, scratch_[w], buffer(id), kept_[id]);
    r = o.result;
    remade_[id] = o.remade;
  } else {
    r = tessellate_surface(scene_->prepared[id], scene_->cameras[f], scene_->frusta[f], scene_->settings, scratch_[w],
                           buffer(id));
    remade_[id] = 1;
  }
  triangles_[id] = r.triangles;
  inconsistent_[id] = r.inconsistencies() > 0;
  capped_[id] = r.capped;
  return r;
}

std::uint64_t FrameWorkload::frame_triangles() const {
  std::uint64_t total = 0;
  for (const std::uint32_t t : triangles_) total += t;
  return total;
}

std::string FrameWorkload::first_inconsistent() const {
  const auto it = std::find(inconsistent_.begin(), inconsistent_.end(), std::uint8_t{1});
  return it == inconsistent_.end() ? std::string()
                                   : scene_->model.surfaces[static_cast<std::size_t>(it - inconsistent_.begin())].name;
}

std::uint64_t FrameWorkload::count(const std::vector<std::uint8_t>& flags) {
  return static_cast<std::uint64_t>(std::count(flags.begin(), flags.end(), std::uint8_t{1}));
}

}  // namespace frontsteal::tess
