// greedy_pipeline.cpp — the tessellation side and the pusher's update of greedy rendering (greedy_pipeline.hpp).
#include "render/greedy_pipeline.hpp"

#include <algorithm>
#include <stdexcept>

#include "render/triangle_renderer.hpp"

namespace frontsteal::render {

GreedySession::GreedySession(const tess::Model& m, std::uint32_t slots, bool reuse) : model_(m) {
  int components = 0;
  for (const tess::Surface& s : m.surfaces) {
    if (s.component < 0) throw std::invalid_argument("greedy rendering needs components (tess::assign_components)");
    components = std::max(components, s.component + 1);
  }
  component_surfaces_.resize(static_cast<std::size_t>(components));
  for (ItemId id = 0; id < m.surfaces.size(); ++id) {
    prepared_.push_back(tess::prepare_surface(m.surfaces[id]));
    component_surfaces_[static_cast<std::size_t>(m.surfaces[id].component)].push_back(id);
  }
  std::vector<std::uint32_t> sizes;
  for (const auto& list : component_surfaces_) sizes.push_back(static_cast<std::uint32_t>(list.size()));
  publication_ = std::make_unique<Publication>(sizes, slots);
  buffers_.assign(slots, std::vector<tess::TriangleBuffers>(m.surfaces.size()));
  slot_view_.assign(sizes.size(), std::vector<int>(slots, -1));
  if (reuse) kept_.assign(slots, std::vector<tess::KeptTessellation>(m.surfaces.size()));
}

std::uint64_t GreedySession::prepare(int view) {
  const std::uint64_t waits = publication_->prepare_frame();
  for (ComponentId c = 0; c < components(); ++c) slot_view_[c][publication_->back_slot(c)] = view;
  return waits;
}

void GreedySession::tessellate(ItemId id, const tess::Camera& camera, const tess::Frustum& frustum,
                               const tess::TessellationSettings& settings, tess::TessellationScratch& scratch,
                               int cost_multiplier) {
  const auto c = static_cast<ComponentId>(model_.surfaces[id].component);
  const SlotIndex slot = publication_->back_slot(c);
  tess::TriangleBuffers& out = buffers_[slot][id];
  // The tessellation-bound mode (frontsteal-paper table2 --cost-multiplier K): the same surface K times into the
  // same back slot (no one reads it before finish_surface); the last result is the published one.
  tess::SurfaceResult r;
  bool remade = true;
  if (!kept_.empty()) {
    const tess::ReuseOutcome o =
        tess::tessellate_or_reuse(prepared_[id], camera, frustum, settings, scratch, out, kept_[slot][id]);
    r = o.result;
    remade = o.remade;
  } else {
    r = tess::tessellate_surface(prepared_[id], camera, frustum, settings, scratch, out);
  }
  for (int k = 1; remade && k < cost_multiplier; ++k)
    tess::tessellate_surface(prepared_[id], camera, frustum, settings, scratch, out);  // the same bytes again
  if (remade) remade_.fetch_add(1, std::memory_order::relaxed);
  if (r.inconsistencies() > 0) inconsistencies_.fetch_add(1, std::memory_order::relaxed);
  publication_->finish_surface(c);
}

GreedyPusher::GreedyPusher(GreedySession& s, bool draw)
    : s_(s), uploaded_(s.components(), {GreedySession::Publication::kNothing, -1}) {
  if (draw) renderer_ = std::make_unique<TriangleRenderer>(s.components());
}

GreedyPusher::~GreedyPusher() = default;

UpdateRecord GreedyPusher::update(int u, const tess::Camera& cam, int current_view, Image* capture) {
  using Clock = std::chrono::steady_clock;
  UpdateRecord rec;
  rec.update = u;
  const auto t0 = Clock::now();
  GreedySession::Publication& publication = s_.publication();
  publication.begin_update();
  if (renderer_) renderer_->begin_frame(cam.view_projection(), cam.eye);
  double lag_sum = 0;
  int drawn = 0;
  for (ComponentId c = 0; c < s_.components(); ++c) {
    const SlotIndex slot = publication.read(c);  // ComponentTris(c), read once
    if (slot == GreedySession::Publication::kNothing) continue;
    const int view = s_.slot_view(c, slot);
    const std::pair<SlotIndex, int> key{slot, view};
    if (renderer_) {
      if (uploaded_[c] != key) {
        surfaces_.clear();
        for (ItemId id : s_.surfaces_of(c)) surfaces_.push_back(&s_.buffer(slot, id));
        renderer_->upload(c, surfaces_);
        ++rec.uploads;
      }
      rec.triangles += renderer_->draw(c);
    } else {
      rec.uploads += uploaded_[c] != key;
      for (ItemId id : s_.surfaces_of(c)) rec.triangles += s_.buffer(slot, id).triangle_count();
    }
    uploaded_[c] = key;
    const int lag = view == current_view ? 0 : u - view;
    lag_sum += lag;
    rec.max_lag = std::max(rec.max_lag, lag);
    ++drawn;
  }
  if (renderer_) {
    if (capture != nullptr)
      *capture = renderer_->read_pixels(cam.width, cam.height);
    else
      renderer_->finish();
  }
  publication.end_update();
  rec.mean_lag = drawn > 0 ? lag_sum / drawn : 0;
  rec.draw_ms = 1e3 * std::chrono::duration<double>(Clock::now() - t0).count();
  return rec;
}

}  // namespace frontsteal::render
