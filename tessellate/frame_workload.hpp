// frame_workload.hpp — the one frame workload every measuring program divides among its workers: a PathScene
// (path_scene.hpp), one scratch per worker, and per surface what its latest tessellation produced (triangles,
// whether its own audit failed, whether the step cap held its deviation bound back).
//
// Why one type: the main job, frontsteal-paper, frontsteal-mpi and the libomp child all run "item `id` of
// frame `f` on worker `w`" and then sum the frame's triangles and audit failures; written once here, the
// item they time and audit is the same code.
//
// OWNERSHIP while a frame runs: run(f, id, w) writes only surface id's slots (each item runs exactly once
// per frame) and worker w's scratch (one thread per worker at a time). The totals are read after the frame,
// once the scheduler's end of frame has ordered every item's writes before the reader.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "tessellate/path_scene.hpp"

namespace frontsteal::tess {

class FrameWorkload {
 public:
  // Refers to `scene` (which must outlive it) with scratch for `workers` workers (at least one).
  FrameWorkload(PathScene& scene, WorkerId workers);

  PathScene& scene() noexcept { return *scene_; }
  const PathScene& scene() const noexcept { return *scene_; }
  ItemId surfaces() const noexcept { return scene_->surfaces(); }
  int frames() const noexcept { return scene_->frames(); }
  WorkerId workers() const noexcept { return static_cast<WorkerId>(scratch_.size()); }
  // Scratch for at least `workers` workers (never shrinks). Not while a frame runs.
  void prepare_workers(WorkerId workers);

  // Tessellates surface `id` of frame `f` with worker w's scratch into the scene's buffer for `id`, and keeps
  // its triangle count and audit flags.
  SurfaceResult run(int f, ItemId id, WorkerId w);

  // Of the latest tessellation of every surface:
  std::uint64_t frame_triangles() const;
  std::uint64_t count_inconsistent() const { return count(inconsistent_); }
  std::uint64_t count_capped() const { return count(capped_); }
  std::string first_inconsistent() const;  // the name of the first surface whose audit failed ("" if none)

 private:
  static std::uint64_t count(const std::vector<std::uint8_t>& flags);
  PathScene* scene_;
  std::vector<TessellationScratch> scratch_;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint8_t> inconsistent_, capped_;
};

}  // namespace frontsteal::tess
