// live_greedy.cpp — greedy rendering with an interactive camera (live_greedy.hpp).
#include "render/live_greedy.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "schedulers/registry.hpp"

namespace frontsteal::render {

namespace {

bool same_view(const tess::Camera& a, const tess::Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fovy_radians == b.fovy_radians &&
         a.width == b.width && a.height == b.height && a.near_plane == b.near_plane && a.far_plane == b.far_plane;
}

const sched::SchedulerInfo& usable(const std::string& name) {
  const sched::SchedulerInfo* info = sched::find_scheduler(name);
  if (info == nullptr) throw std::invalid_argument("unknown scheduler '" + name + "'");
  if (info->contract != Contract::kExactlyOnce) {
    throw std::invalid_argument("scheduler '" + name +
                                "' is at-least-once: a surface run twice would break its component's count-down");
  }
  return *info;
}

}  // namespace

std::vector<std::string> LiveGreedy::scheduler_names() {
  std::vector<std::string> out;
  for (const sched::SchedulerInfo& info : sched::scheduler_registry()) {
    if (info.contract == Contract::kExactlyOnce && !info.variant) out.push_back(info.name);
  }
  return out;
}

LiveGreedy::LiveGreedy(const tess::Model& model, WorkerId tessellators, std::uint32_t slots,
                       const std::string& scheduler, const tess::TessellationSettings& settings, bool reuse)
    : session_(model, slots, reuse), tessellators_(tessellators), settings_(settings), scheduler_(scheduler) {
  if (tessellators < 1) throw std::invalid_argument("at least one tessellator");
  if (slots < 2) throw std::invalid_argument("a component needs at least 2 slots");
  usable(scheduler);
  request_.scheduler = scheduler;
  driver_ = std::thread([this] { drive(); });
}

LiveGreedy::~LiveGreedy() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  driver_.join();
}

void LiveGreedy::start_drawing() { pusher_ = std::make_unique<GreedyPusher>(session_, true); }
void LiveGreedy::stop_drawing() { pusher_.reset(); }

void LiveGreedy::set_tolerance(double pixels) {
  settings_.pixel_tolerance = pixels;
  view_dirty_ = true;
}

void LiveGreedy::set_scheduler(const std::string& name) {
  usable(name);
  scheduler_ = name;
  {
    std::lock_guard lock(mutex_);
    request_.scheduler = name;
  }
  changed_.notify_all();
}

LiveCounters LiveGreedy::counters() const {
  std::lock_guard lock(mutex_);
  return counters_;
}

void LiveGreedy::ask(const tess::Camera& camera) {
  current_view_ = updates_;
  {
    std::lock_guard lock(mutex_);
    request_.view = current_view_;
    request_.camera = camera;
    request_.settings = settings_;
  }
  changed_.notify_all();
}

UpdateRecord LiveGreedy::update(const tess::Camera& camera, Image* capture) {
  if (!pusher_) start_drawing();
  if (view_dirty_ || current_view_ < 0 || !same_view(camera, last_camera_)) ask(camera);
  view_dirty_ = false;
  last_camera_ = camera;
  {
    std::unique_lock lock(mutex_);
    if (synchronized_) changed_.wait(lock, [&] { return done_view_ >= current_view_ || !error_.empty(); });
    if (!error_.empty()) throw std::runtime_error("tessellation driver: " + error_);
  }
  return pusher_->update(updates_++, camera, current_view_, capture);
}

void LiveGreedy::drive() {
  std::unique_ptr<sched::Scheduler> scheduler;
  std::string scheduler_name;
  std::vector<tess::TessellationScratch> scratch;
  int last_view = -1;
  const auto items = static_cast<ItemId>(session_.model().surfaces.size());
  try {
    for (;;) {
      Request r;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock,
                      [&] { return stop_ || request_.view != last_view || request_.scheduler != scheduler_name; });
        if (stop_) return;
        if (request_.view < 0) {  // only the scheduler changed before the first view: nothing to tessellate yet
          last_view = request_.view;
          scheduler_name = request_.scheduler;
          scheduler.reset();
          continue;
        }
        r = request_;
      }
      if (!scheduler || r.scheduler != scheduler_name) {
        scheduler.reset();  // its threads end before the next one's start
        scheduler = usable(r.scheduler).make({.workers = tessellators_, .items = items, .seed = 1}, {});
        scheduler_name = r.scheduler;
        scratch.assign(scheduler->worker_count(), {});
      }
      last_view = r.view;
      const std::uint64_t waits = session_.prepare(r.view);
      const tess::Frustum frustum = tess::Frustum::of(r.camera);
      auto process = [&](ItemId id, WorkerId w) { session_.tessellate(id, r.camera, frustum, r.settings, scratch[w]); };
      const std::uint64_t remade_before = session_.remade();
      const auto t0 = std::chrono::steady_clock::now();
      const FrameStats& st = scheduler->run_frame(process);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      {
        std::lock_guard lock(mutex_);
        const std::uint64_t steals = st.totals().steals_succeeded;
        counters_.scheduler = scheduler_name;
        ++counters_.tessellation_frames;
        counters_.steals += steals;
        counters_.last_frame_steals = steals;
        counters_.last_frame_ms = ms;
        counters_.driver_waits += waits;
        counters_.inconsistencies = session_.inconsistencies();
        counters_.last_frame_remade = session_.remade() - remade_before;
        done_view_ = r.view;
      }
      changed_.notify_all();
    }
  } catch (const std::exception& e) {
    {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    changed_.notify_all();
  }
}

}  // namespace frontsteal::render
