// frame_workload.cpp — items of a frame and their totals (frame_workload.hpp).
#include "tessellate/frame_workload.hpp"

#include <algorithm>

namespace frontsteal::tess {

FrameWorkload::FrameWorkload(PathScene& scene, WorkerId workers)
    : scene_(&scene),
      scratch_(std::max<WorkerId>(1, workers)),
      triangles_(scene.surfaces(), 0),
      inconsistent_(scene.surfaces(), 0),
      capped_(scene.surfaces(), 0) {}

void FrameWorkload::prepare_workers(WorkerId workers) {
  if (scratch_.size() < workers) scratch_.resize(workers);
}

SurfaceResult FrameWorkload::run(int f, ItemId id, WorkerId w) {
  const SurfaceResult r = scene_->tessellate(f, id, scratch_[w]);
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
