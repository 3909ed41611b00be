#include "render/greedy_renderer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "core/component_publication.hpp"
#include "core/publication_policies.hpp"
#include "core/stealing_scheduler.hpp"
#include "core/std_backend.hpp"
#include "render/headless_gl.hpp"
#include "render/triangle_renderer.hpp"

namespace frontsteal::render {

namespace {

using Clock = std::chrono::steady_clock;
using Publication = ComponentPublication<StdBackend, PublicationOrders>;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Everything both modes share: the model's per-frame inputs, the slots' triangle buffers, the publication.
struct Session {
  const tess::Model& model;
  const GreedyOptions& options;
  tess::Box box;
  std::vector<tess::PreparedSurface> prepared;
  std::vector<std::vector<ItemId>> component_surfaces;  // component -> its surfaces
  std::vector<std::vector<tess::TriangleBuffers>> buffers;  // [slot][surface]
  std::vector<std::vector<int>> slot_view;  // [component][slot]: path frame the slot was tessellated for
  std::unique_ptr<Publication> publication;
  // Surface tessellations whose own audit failed (surface_tessellator.hpp, step 6); tessellators add, the
  // driver reads after they stopped. Relaxed: a count, ordered by the threads' join.
  std::atomic<std::uint64_t> inconsistencies{0};

  Session(const tess::Model& m, const GreedyOptions& o) : model(m), options(o), box(tess::model_box(m)) {
    int components = 0;
    for (const tess::Surface& s : m.surfaces) {
      if (s.component < 0) throw std::invalid_argument("greedy rendering needs components (tess::assign_components)");
      components = std::max(components, s.component + 1);
    }
    component_surfaces.resize(static_cast<std::size_t>(components));
    for (ItemId id = 0; id < m.surfaces.size(); ++id) {
      prepared.push_back(tess::prepare_surface(m.surfaces[id]));
      component_surfaces[static_cast<std::size_t>(m.surfaces[id].component)].push_back(id);
    }
    std::vector<std::uint32_t> sizes;
    for (const auto& list : component_surfaces) sizes.push_back(static_cast<std::uint32_t>(list.size()));
    publication = std::make_unique<Publication>(sizes, o.slots);
    buffers.assign(o.slots, std::vector<tess::TriangleBuffers>(m.surfaces.size()));
    slot_view.assign(sizes.size(), std::vector<int>(o.slots, -1));
  }

  ComponentId components() const { return static_cast<ComponentId>(component_surfaces.size()); }
  tess::Camera camera(int update) const {
    return tess::camera_on(options.path, box, update, options.updates, options.width, options.height);
  }
  // Driver, between frames: back slots for a frame tessellated for path frame `view`.
  std::uint64_t prepare(int view) {
    const std::uint64_t waits = publication->prepare_frame();
    for (ComponentId c = 0; c < components(); ++c) slot_view[c][publication->back_slot(c)] = view;
    return waits;
  }
  // Tessellator: one surface into its component's back slot, then the component's count-down (and swap).
  void tessellate(ItemId id, const tess::Camera& camera, const tess::Frustum& frustum, tess::TessellationScratch& scratch) {
    const auto c = static_cast<ComponentId>(model.surfaces[id].component);
    tess::TriangleBuffers& out = buffers[publication->back_slot(c)][id];
    // The tessellation-bound mode (cost_multiplier K): the same surface K times into the same back slot (no
    // one reads it before finish_surface); the last result is the published one.
    for (int k = 1; k < options.cost_multiplier; ++k) tess::tessellate_surface(prepared[id], camera, frustum, options.settings, scratch, out);
    const tess::SurfaceResult r = tess::tessellate_surface(prepared[id], camera, frustum, options.settings, scratch, out);
    if (r.inconsistencies() > 0) inconsistencies.fetch_add(1, std::memory_order::relaxed);
    publication->finish_surface(c);
  }
};

// The pusher's side: one update, with OpenGL or counting only.
class Pusher {
 public:
  Pusher(Session& s, HeadlessGL* gl) : s_(s), gl_(gl), uploaded_(s.components(), {Publication::kNothing, -1}) {
    if (gl_ != nullptr) renderer_ = std::make_unique<TriangleRenderer>(s.components());
  }

  UpdateRecord update(int u, bool capture, Image* image) {
    UpdateRecord rec;
    rec.update = u;
    const auto t0 = Clock::now();
    const tess::Camera cam = s_.camera(u);
    s_.publication->begin_update();
    if (renderer_) renderer_->begin_frame(cam.view_projection(), cam.eye);
    double lag_sum = 0;
    int drawn = 0;
    for (ComponentId c = 0; c < s_.components(); ++c) {
      const SlotIndex slot = s_.publication->read(c);  // ComponentTris(c), read once
      if (slot == Publication::kNothing) continue;
      const int view = s_.slot_view[c][slot];
      const std::pair<SlotIndex, int> key{slot, view};
      if (renderer_) {
        if (uploaded_[c] != key) {
          surfaces_.clear();
          for (ItemId id : s_.component_surfaces[c]) surfaces_.push_back(&s_.buffers[slot][id]);
          renderer_->upload(c, surfaces_);
          ++rec.uploads;
        }
        rec.triangles += renderer_->draw(c);
      } else {
        rec.uploads += uploaded_[c] != key;
        for (ItemId id : s_.component_surfaces[c]) rec.triangles += s_.buffers[slot][id].triangle_count();
      }
      uploaded_[c] = key;
      const int lag = u - view;
      lag_sum += lag;
      rec.max_lag = std::max(rec.max_lag, lag);
      ++drawn;
    }
    if (renderer_) {
      if (capture && image != nullptr) *image = renderer_->read_pixels(gl_->width(), gl_->height());
      else renderer_->finish();
    }
    s_.publication->end_update();
    rec.mean_lag = drawn > 0 ? lag_sum / drawn : 0;
    rec.draw_ms = 1e3 * seconds_since(t0);
    return rec;
  }

  TriangleRenderer* renderer() { return renderer_.get(); }

 private:
  Session& s_;
  HeadlessGL* gl_;
  std::unique_ptr<TriangleRenderer> renderer_;
  std::vector<std::pair<SlotIndex, int>> uploaded_;  // (slot, view) each component's GL buffers hold
  std::vector<const tess::TriangleBuffers*> surfaces_;
};

std::vector<int> sample_updates(const GreedyOptions& o) {
  std::vector<int> out;
  if (o.null_renderer) return out;
  for (int k = 0; k < o.samples; ++k) out.push_back(static_cast<int>((k + 1.0) * o.updates / (o.samples + 1.0)));
  return out;
}

void pace(const GreedyOptions& o, Clock::time_point start, int u) {
  if (o.display_rate <= 0) return;
  std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(u / o.display_rate)));
}

std::string png_path(const GreedyOptions& o, const std::string& stem, int u) {
  char name[64];
  std::snprintf(name, sizeof name, "%s-%04d.png", stem.c_str(), u);
  return o.out_dir + "/" + name;
}

void validate(const GreedyOptions& o) {
  if (o.updates < 1) throw std::invalid_argument("updates must be at least 1");
  if (o.cost_multiplier < 1) throw std::invalid_argument("cost_multiplier must be at least 1");
  if (o.slots < 2) throw std::invalid_argument("a component needs at least 2 slots");
  if (o.tessellators < 1) throw std::invalid_argument("at least one tessellator");
  if (o.display_rate < 0) throw std::invalid_argument("the display rate must not be negative");
  if (o.samples < 0 || o.png_every < 0) throw std::invalid_argument("samples and png-every must not be negative");
}

}  // namespace

GreedyStats run_greedy(const tess::Model& model, const GreedyOptions& o) {
  validate(o);
  Session s(model, o);
  GreedyStats stats;
  std::optional<HeadlessGL> gl;
  if (!o.null_renderer) gl.emplace(o.width, o.height);
  stats.renderer = gl ? gl->description() : "null renderer (counts triangles, draws nothing)";
  const std::vector<int> samples = sample_updates(o);
  std::vector<std::pair<int, Image>> lagging;  // sampled updates' images
  const auto wants_image = [&](int u) {
    return std::find(samples.begin(), samples.end(), u) != samples.end() || (o.png_every > 0 && u % o.png_every == 0);
  };
  const auto keep_image = [&](int u, Image&& image) {
    if (o.png_every > 0 && u % o.png_every == 0 && !o.out_dir.empty()) write_png(image, png_path(o, "frame", u));
    if (std::find(samples.begin(), samples.end(), u) != samples.end()) lagging.emplace_back(u, std::move(image));
  };
  std::atomic<std::uint64_t> frames_done{0};  // for progress lines from the pusher thread
  const auto report = [&](int u) {
    if (o.progress && (u + 1) % std::max(1, o.updates / 10) == 0) {
      o.progress("update " + std::to_string(u + 1) + "/" + std::to_string(o.updates) + ", tessellation frames " +
                 std::to_string(o.single_thread ? stats.tessellation_frames : frames_done.load(std::memory_order::relaxed)));
    }
  };
  const auto start = Clock::now();

  if (!o.single_thread) {
    stats.mode = "multi-threaded: pusher + " + std::to_string(o.tessellators) + " tessellator(s), stealing (Fenced)";
    std::atomic<int> current_view{0};
    std::atomic<bool> pusher_done{false};
    std::exception_ptr pusher_error;
    std::thread pusher_thread([&] {
      try {
        if (gl) gl->make_current();
        Pusher pusher(s, gl ? &*gl : nullptr);
        for (int u = 0; u < o.updates; ++u) {
          pace(o, start, u);
          current_view.store(u, std::memory_order::relaxed);
          Image image;
          UpdateRecord rec = pusher.update(u, wants_image(u), &image);
          rec.at_seconds = seconds_since(start);
          stats.per_update.push_back(rec);
          if (!image.rgb.empty()) keep_image(u, std::move(image));
          report(u);
        }
      } catch (...) {
        pusher_error = std::current_exception();
      }
      if (gl) gl->release();
      pusher_done.store(true, std::memory_order::release);
    });
    {
      StealingScheduler<Fenced> scheduler({.workers = o.tessellators, .items = static_cast<ItemId>(model.surfaces.size()), .seed = 1});
      std::vector<tess::TessellationScratch> scratch(o.tessellators);
      int last_view = -1;
      while (!pusher_done.load(std::memory_order::acquire)) {
        const int view = current_view.load(std::memory_order::relaxed);  // the current view matrix
        if (view == last_view) {  // this view is tessellated already: wait for the pusher's next one
          std::this_thread::sleep_for(std::chrono::microseconds(100));
          continue;
        }
        last_view = view;
        stats.driver_waits += s.prepare(view);
        const tess::Camera cam = s.camera(view);
        const tess::Frustum frustum = tess::Frustum::of(cam);
        scheduler.run_frame([&](ItemId id, WorkerId w) { s.tessellate(id, cam, frustum, scratch[w]); });
        ++stats.tessellation_frames;
        frames_done.store(stats.tessellation_frames, std::memory_order::relaxed);
        stats.surfaces_tessellated += model.surfaces.size();
      }
    }
    pusher_thread.join();
    if (pusher_error) std::rethrow_exception(pusher_error);
  } else {
    stats.mode = "single-threaded: §5.3 budget 1/R - m*t_p per update";
    if (gl) gl->make_current();
    Pusher pusher(s, gl ? &*gl : nullptr);
    tess::TessellationScratch scratch;
    ItemId next = static_cast<ItemId>(model.surfaces.size());  // next surface of the current frame
    tess::Camera cam = s.camera(0);
    tess::Frustum frustum = tess::Frustum::of(cam);
    double seconds_per_triangle = 0;
    int frame_view = -1;  // the path frame the current tessellation frame is for
    const double period = o.display_rate > 0 ? 1.0 / o.display_rate : 0.0;
    for (int u = 0; u < o.updates; ++u) {
      pace(o, start, u);
      Image image;
      UpdateRecord rec = pusher.update(u, wants_image(u), &image);
      rec.at_seconds = seconds_since(start);
      if (rec.triangles > 0) seconds_per_triangle = 1e-3 * rec.draw_ms / static_cast<double>(rec.triangles);
      const double budget = std::max(0.0, period - static_cast<double>(rec.triangles) * seconds_per_triangle);
      rec.budget_ms = 1e3 * budget;
      const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(budget));
      do {  // at least one surface per update, so tessellation cannot starve
        if (next == model.surfaces.size() && frame_view == u) break;  // this view is tessellated already
        if (next == model.surfaces.size()) {
          frame_view = u;
          if (stats.surfaces_tessellated > 0) ++stats.tessellation_frames;  // the frame just finished
          stats.driver_waits += s.prepare(u);
          cam = s.camera(u);
          frustum = tess::Frustum::of(cam);
          next = 0;
        }
        s.tessellate(next++, cam, frustum, scratch);
        ++stats.surfaces_tessellated;
      } while (Clock::now() < deadline);
      stats.per_update.push_back(rec);
      if (!image.rgb.empty()) keep_image(u, std::move(image));
      report(u);
    }
    if (next == model.surfaces.size() && stats.surfaces_tessellated > 0) ++stats.tessellation_frames;
    if (gl) gl->release();
  }
  stats.seconds = seconds_since(start);
  stats.updates = o.updates;
  stats.tessellation_inconsistencies = s.inconsistencies.load(std::memory_order::relaxed);

  // Statistics.
  double lag = 0, triangles = 0;
  for (const UpdateRecord& r : stats.per_update) {
    lag += r.mean_lag;
    triangles += static_cast<double>(r.triangles);
    stats.max_lag = std::max(stats.max_lag, r.max_lag);
  }
  const double n = std::max<std::size_t>(1, stats.per_update.size());
  stats.mean_lag = lag / n;
  stats.mean_triangles = triangles / n;
  stats.updates_per_second = stats.updates / stats.seconds;
  stats.tessellations_per_second = static_cast<double>(stats.surfaces_tessellated) / model.surfaces.size() / stats.seconds;
  stats.surfaces_per_second = static_cast<double>(stats.surfaces_tessellated) / stats.seconds;

  // Lagging against synchronized images of the same views (the paper's colour plate).
  if (gl && !lagging.empty()) {
    if (o.progress) o.progress("rendering " + std::to_string(lagging.size()) + " synchronized reference frames");
    gl->make_current();
    double worst = -1;
    for (auto& [u, image] : lagging) {
      const Image reference = render_synchronized(model, s.camera(u), o.settings);
      QualitySample q;
      q.update = u;
      q.mean_lag = stats.per_update[static_cast<std::size_t>(u)].mean_lag;
      q.psnr_db = psnr(image, reference);
      q.ssim = ssim(image, reference);
      if (!o.out_dir.empty()) {
        q.lagging_png = png_path(o, "lagging", u);
        q.synchronized_png = png_path(o, "synchronized", u);
        write_png(image, q.lagging_png);
        write_png(reference, q.synchronized_png);
        if (q.mean_lag > worst) {
          worst = q.mean_lag;
          Image plate(2 * image.width + 8, image.height);
          for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < plate.width; ++x) {
              std::uint8_t* d = &plate.rgb[(static_cast<std::size_t>(y) * plate.width + x) * 3];
              const std::uint8_t* src = x < image.width ? image.pixel(x, y)
                                        : x >= image.width + 8 ? reference.pixel(x - image.width - 8, y) : nullptr;
              for (int c = 0; c < 3; ++c) d[c] = src ? src[c] : 255;
            }
          }
          stats.colour_plate_png = o.out_dir + "/colour-plate.png";
          write_png(plate, stats.colour_plate_png);
        }
      }
      stats.quality.push_back(q);
    }
    gl->release();
  }
  return stats;
}

Image render_synchronized(const tess::Model& model, const tess::Camera& camera, const tess::TessellationSettings& settings,
                          std::uint64_t* triangles) {
  int components = 0;
  for (const tess::Surface& s : model.surfaces) components = std::max(components, s.component + 1);
  std::vector<std::vector<const tess::TriangleBuffers*>> per_component(static_cast<std::size_t>(std::max(components, 1)));
  std::vector<tess::TriangleBuffers> buffers(model.surfaces.size());
  tess::TessellationScratch scratch;
  const tess::Frustum frustum = tess::Frustum::of(camera);
  for (std::size_t id = 0; id < model.surfaces.size(); ++id) {
    tess::tessellate_surface(tess::prepare_surface(model.surfaces[id]), camera, frustum, settings, scratch, buffers[id]);
    per_component[static_cast<std::size_t>(std::max(model.surfaces[id].component, 0))].push_back(&buffers[id]);
  }
  TriangleRenderer renderer(static_cast<std::uint32_t>(per_component.size()));
  std::uint64_t drawn = 0;
  for (std::uint32_t c = 0; c < per_component.size(); ++c) renderer.upload(c, per_component[c]);
  renderer.begin_frame(camera.view_projection(), camera.eye);
  for (std::uint32_t c = 0; c < per_component.size(); ++c) drawn += renderer.draw(c);
  if (triangles != nullptr) *triangles = drawn;
  return renderer.read_pixels(camera.width, camera.height);
}

}  // namespace frontsteal::render
