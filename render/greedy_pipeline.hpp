// greedy_pipeline.hpp — the two halves of greedy rendering (paper §5), shared by the batch run
// (run_greedy, frontsteal-render) and the interactive viewer (LiveGreedy, frontsteal-view), so that both draw
// with the same pusher and tessellate with the same per-surface code; only who picks the camera differs.
//
//   GreedySession  the tessellation side: prepared surfaces, the slots' triangle buffers, the per-component
//                  publication (core/component_publication.hpp), and which view each slot was tessellated for.
//   GreedyPusher   the pusher's update: begin_update, read each component's slot once, upload it if it changed,
//                  draw, end_update. It never waits for tessellators. It draws with TriangleRenderer in
//                  whatever OpenGL context is current on its thread (HeadlessGL's surfaceless EGL context and
//                  framebuffer object, or a GLFW window's default framebuffer), or, without a renderer, only counts.
//
// View ids: the driver tags every tessellation frame with the id of the view it was started for; the pusher's
// lag of a component is 0 when its triangles are for the current view, else (update − view id). The batch run
// uses the path frame as both update and view id (lag = u − view, Table 2); the viewer gives a new view id (the
// update number) only when the camera or the tolerance changes, so a still camera shows lag 0.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/component_publication.hpp"
#include "core/id_range.hpp"
#include "core/publication_policies.hpp"
#include "core/std_backend.hpp"
#include "render/greedy_renderer.hpp"
#include "render/image.hpp"
#include "tessellate/camera.hpp"
#include "tessellate/model.hpp"
#include "tessellate/surface_reuse.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::render {

class TriangleRenderer;

class GreedySession {
 public:
  using Publication = ComponentPublication<StdBackend, PublicationOrders>;

  // `model` must have components assigned (tess::assign_components); throws std::invalid_argument otherwise.
  // `reuse`: a surface whose steps and trim polylines did not change since its back slot's buffer was made keeps
  // that buffer (tessellate/surface_reuse.hpp: the same bytes as recomputing them), as the paper's renderer does.
  GreedySession(const tess::Model& model, std::uint32_t slots, bool reuse = false);

  const tess::Model& model() const noexcept { return model_; }
  ComponentId components() const noexcept { return static_cast<ComponentId>(component_surfaces_.size()); }
  const std::vector<ItemId>& surfaces_of(ComponentId c) const { return component_surfaces_[c]; }
  Publication& publication() noexcept { return *publication_; }
  const tess::TriangleBuffers& buffer(SlotIndex slot, ItemId id) const { return buffers_[slot][id]; }
  int slot_view(ComponentId c, SlotIndex slot) const { return slot_view_[c][slot]; }

  // Driver, between frames: back slots for a frame tessellated for view `view`; returns the driver's waits.
  std::uint64_t prepare(int view);
  // Tessellator: one surface into its component's back slot, then the component's count-down (and swap).
  void tessellate(ItemId id, const tess::Camera& camera, const tess::Frustum& frustum,
                  const tess::TessellationSettings& settings, tess::TessellationScratch& scratch,
                  int cost_multiplier = 1);
  // Surface tessellations whose own audit failed (surface_tessellator.hpp, step 6); with reuse, a kept buffer's
  // audit counts again each time it is reused.
  std::uint64_t inconsistencies() const noexcept { return inconsistencies_.load(std::memory_order::relaxed); }
  // Surfaces actually tessellated (not reused) so far.
  std::uint64_t remade() const noexcept { return remade_.load(std::memory_order::relaxed); }

 private:
  const tess::Model& model_;
  std::vector<tess::PreparedSurface> prepared_;
  std::vector<std::vector<ItemId>> component_surfaces_;      // component -> its surfaces
  std::vector<std::vector<tess::TriangleBuffers>> buffers_;  // [slot][surface]
  std::vector<std::vector<int>> slot_view_;                  // [component][slot]: view the slot was tessellated for
  std::vector<std::vector<tess::KeptTessellation>> kept_;    // [slot][surface], with reuse (else empty)
  std::unique_ptr<Publication> publication_;
  // Tessellators add, the driver reads after they stopped. Relaxed: a count, ordered by the threads' join.
  std::atomic<std::uint64_t> inconsistencies_{0};
  std::atomic<std::uint64_t> remade_{0};
};

class GreedyPusher {
 public:
  // draw: create a TriangleRenderer in the OpenGL context current on this thread (and use it for every update,
  // on this thread only); else count what would be drawn.
  GreedyPusher(GreedySession& session, bool draw);
  ~GreedyPusher();
  GreedyPusher(const GreedyPusher&) = delete;
  GreedyPusher& operator=(const GreedyPusher&) = delete;

  // Update u with `camera` (its width × height is the viewport); `current_view` is the id of the view this
  // update shows (see above). With `capture` non-null and a renderer, reads the image back into it.
  UpdateRecord update(int u, const tess::Camera& camera, int current_view, Image* capture);

 private:
  GreedySession& s_;
  std::unique_ptr<TriangleRenderer> renderer_;
  std::vector<std::pair<SlotIndex, int>> uploaded_;  // (slot, view) each component's GL buffers hold
  std::vector<const tess::TriangleBuffers*> surfaces_;
};

}  // namespace frontsteal::render
