#include "render/greedy_renderer.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>

#include "core/stealing_scheduler.hpp"
#include "render/greedy_pipeline.hpp"
#include "render/headless_gl.hpp"
#include "render/triangle_renderer.hpp"

namespace frontsteal::render {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::vector<int> sample_updates(const GreedyOptions& o) {
  std::vector<int> out;
  if (o.null_renderer) return out;
  for (int k = 0; k < o.samples; ++k) out.push_back(static_cast<int>((k + 1.0) * o.updates / (o.samples + 1.0)));
  return out;
}

void pace(const GreedyOptions& o, Clock::time_point start, int u) {
  if (o.display_rate <= 0) return;
  std::this_thread::sleep_until(
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(u / o.display_rate)));
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
  GreedySession s(model, o.slots, o.reuse);
  const tess::Box box = tess::model_box(model);
  const auto camera = [&](int update) {  // path frame `update` (the batch run's view id)
    return tess::camera_on(o.path, box, update, o.updates, o.width, o.height);
  };
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
      o.progress(
          "update " + std::to_string(u + 1) + "/" + std::to_string(o.updates) + ", tessellation frames " +
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
        GreedyPusher pusher(s, gl.has_value());
        for (int u = 0; u < o.updates; ++u) {
          pace(o, start, u);
          current_view.store(u, std::memory_order::relaxed);
          Image image;
          UpdateRecord rec = pusher.update(u, camera(u), u, wants_image(u) ? &image : nullptr);
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
      StealingScheduler<Fenced> scheduler(
          {.workers = o.tessellators, .items = static_cast<ItemId>(model.surfaces.size()), .seed = 1});
      std::vector<tess::TessellationScratch> scratch(o.tessellators);
      int last_view = -1;
      // At least one tessellation frame, even when the pusher ends first: a loaded machine can delay this loop
      // past a short run's last update (a 12-update test once ended with no tessellation at all under load).
      while (stats.tessellation_frames == 0 || !pusher_done.load(std::memory_order::acquire)) {
        const int view = current_view.load(std::memory_order::relaxed);  // the current view matrix
        if (view == last_view) {  // this view is tessellated already: wait for the pusher's next one
          std::this_thread::sleep_for(std::chrono::microseconds(100));
          continue;
        }
        last_view = view;
        stats.driver_waits += s.prepare(view);
        const tess::Camera cam = camera(view);
        const tess::Frustum frustum = tess::Frustum::of(cam);
        scheduler.run_frame(
            [&](ItemId id, WorkerId w) { s.tessellate(id, cam, frustum, o.settings, scratch[w], o.cost_multiplier); });
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
    GreedyPusher pusher(s, gl.has_value());
    tess::TessellationScratch scratch;
    ItemId next = static_cast<ItemId>(model.surfaces.size());  // next surface of the current frame
    tess::Camera cam = camera(0);
    tess::Frustum frustum = tess::Frustum::of(cam);
    double seconds_per_triangle = 0;
    int frame_view = -1;  // the path frame the current tessellation frame is for
    const double period = o.display_rate > 0 ? 1.0 / o.display_rate : 0.0;
    for (int u = 0; u < o.updates; ++u) {
      pace(o, start, u);
      Image image;
      UpdateRecord rec = pusher.update(u, camera(u), u, wants_image(u) ? &image : nullptr);
      rec.at_seconds = seconds_since(start);
      if (rec.triangles > 0) seconds_per_triangle = 1e-3 * rec.draw_ms / static_cast<double>(rec.triangles);
      const double budget = std::max(0.0, period - static_cast<double>(rec.triangles) * seconds_per_triangle);
      rec.budget_ms = 1e3 * budget;
      const auto deadline =
          Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(budget));
      do {  // at least one surface per update, so tessellation cannot starve
        if (next == model.surfaces.size() && frame_view == u) break;  // this view is tessellated already
        if (next == model.surfaces.size()) {
          frame_view = u;
          if (stats.surfaces_tessellated > 0) ++stats.tessellation_frames;  // the frame just finished
          stats.driver_waits += s.prepare(u);
          cam = camera(u);
          frustum = tess::Frustum::of(cam);
          next = 0;
        }
        s.tessellate(next++, cam, frustum, o.settings, scratch, o.cost_multiplier);
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
  stats.tessellation_inconsistencies = s.inconsistencies();
  stats.surfaces_remade = s.remade();

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
  stats.tessellations_per_second =
      static_cast<double>(stats.surfaces_tessellated) / model.surfaces.size() / stats.seconds;
  stats.surfaces_per_second = static_cast<double>(stats.surfaces_tessellated) / stats.seconds;

  // Lagging against synchronized images of the same views (the paper's colour plate).
  if (gl && !lagging.empty()) {
    if (o.progress) o.progress("rendering " + std::to_string(lagging.size()) + " synchronized reference frames");
    gl->make_current();
    double worst = -1;
    for (auto& [u, image] : lagging) {
      const Image reference = render_synchronized(model, camera(u), o.settings);
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
              const std::uint8_t* src = x < image.width        ? image.pixel(x, y)
                                        : x >= image.width + 8 ? reference.pixel(x - image.width - 8, y)
                                                               : nullptr;
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

Image render_synchronized(const tess::Model& model, const tess::Camera& camera,
                          const tess::TessellationSettings& settings, std::uint64_t* triangles) {
  int components = 0;
  for (const tess::Surface& s : model.surfaces) components = std::max(components, s.component + 1);
  std::vector<std::vector<const tess::TriangleBuffers*>> per_component(
      static_cast<std::size_t>(std::max(components, 1)));
  std::vector<tess::TriangleBuffers> buffers(model.surfaces.size());
  tess::TessellationScratch scratch;
  const tess::Frustum frustum = tess::Frustum::of(camera);
  for (std::size_t id = 0; id < model.surfaces.size(); ++id) {
    tess::tessellate_surface(tess::prepare_surface(model.surfaces[id]), camera, frustum, settings, scratch,
                             buffers[id]);
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
