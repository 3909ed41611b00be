// frame_workload.hpp — the one frame workload every measuring program divides among its workers: a PathScene
// (path_scene.hpp), one scratch per worker, and per surface what its latest tessellation produced (triangles,
// whether its own audit failed, whether the step cap held its deviation bound back).
//
// With reuse on (surface_reuse.hpp) a surface whose key did not change since its buffer was made keeps its
// triangles: the frame's work becomes the surfaces whose steps changed, and count_remade() says how many. The
// triangle counts and audit flags are those of the buffer either way, so the totals (and the audits against a
// serial reference) do not depend on reuse; what a frame costs does depend on the frame before it, so a
// measurement that compares runs of the same frames starts each of them from the same state (prime()).
//
// Why one type: the main job, frontsteal-paper, frontsteal-mpi and the libomp child all run "item `id` of
// frame `f` on worker `w`" and then sum the frame's triangles and audit failures; written once here, the
// item they time and audit is the same code.
//
// OWNERSHIP while a frame runs: run(f, id, w) writes only surface id's slots (each item runs exactly once
// per frame) and worker w's scratch (one thread per worker at a time). The totals are read after the frame,
// once the scheduler's end of frame has ordered every item's writes before the reader. With Buffers::kOwn the
// triangles go to buffers of this workload's own instead of the scene's, so several workloads over one scene
// can each run a whole frame at the same time (the main job's limit arm: P serial loops at once).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "tessellate/path_scene.hpp"
#include "tessellate/surface_reuse.hpp"

namespace frontsteal::tess {

class FrameWorkload {
 public:
  enum class Buffers { kScene, kOwn };  // where run() writes a surface's triangles

  // Refers to `scene` (which must outlive it) with scratch for `workers` workers (at least one).
  FrameWorkload(PathScene& scene, WorkerId workers, Buffers buffers = Buffers::kScene);

  PathScene& scene() noexcept { return *scene_; }
  const PathScene& scene() const noexcept { return *scene_; }
  ItemId surfaces() const noexcept { return scene_->surfaces(); }
  int frames() const noexcept { return scene_->frames(); }
  WorkerId workers() const noexcept { return static_cast<WorkerId>(scratch_.size()); }
  // Scratch for at least `workers` workers (never shrinks). Not while a frame runs.
  void prepare_workers(WorkerId workers);

  // Frame-to-frame reuse (off by default). Not while a frame runs.
  void set_reuse(bool on);
  bool reuse() const noexcept { return reuse_; }
  // Reuse on: the state a run of frames first.. starts from, made the same whatever ran before — nothing kept
  // for first = 0, otherwise frame first − 1 run here, serially on worker 0 (only what changed is remade).
  // Reuse off: nothing to do. Not while a frame runs.
  void prime(int first);

  // Tessellates surface `id` of frame `f` with worker w's scratch into the scene's buffer for `id` (or, with
  // reuse, keeps the buffer when its key is unchanged), and keeps its triangle count and audit flags.
  SurfaceResult run(int f, ItemId id, WorkerId w);

  // Of the latest tessellation of every surface:
  std::uint64_t frame_triangles() const;
  std::uint64_t count_inconsistent() const { return count(inconsistent_); }
  std::uint64_t count_capped() const { return count(capped_); }
  std::string first_inconsistent() const;  // the name of the first surface whose audit failed ("" if none)
  // Surfaces tessellated by the latest frame's items (with reuse off: all of them, culled ones included).
  std::uint64_t count_remade() const { return count(remade_); }

 private:
  static std::uint64_t count(const std::vector<std::uint8_t>& flags);
  TriangleBuffers& buffer(ItemId id) noexcept { return own_.empty() ? scene_->buffers[id] : own_[id]; }
  PathScene* scene_;
  std::vector<TriangleBuffers> own_;  // Buffers::kOwn: one per surface; empty: the scene's
  std::vector<TessellationScratch> scratch_;
  std::vector<KeptTessellation> kept_;  // per surface, with reuse on
  bool reuse_ = false;
  std::vector<std::uint32_t> triangles_;
  std::vector<std::uint8_t> inconsistent_, capped_, remade_;
};

}  // namespace frontsteal::tess
