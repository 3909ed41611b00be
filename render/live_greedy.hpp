// live_greedy.hpp — greedy rendering driven by an interactive camera (frontsteal-view): the batch run's pusher and
// tessellation code (greedy_pipeline.hpp), with the camera, the tolerance, the scheduler and the mode chosen while
// it runs.
//
// Threads: the caller is the pusher (it owns the OpenGL context, e.g. a GLFW window's, and calls update() once
// per displayed frame); one driver thread runs tessellation frames on a scheduler from the registry
// (schedulers/registry.hpp), each for the newest view the pusher asked for when the frame starts.
//   lagging       update() never waits: it draws whatever each component last published (paper §5).
//   synchronized  update() waits until a tessellation frame for its own view has finished, so every component is
//                 drawn for the current view (lag 0): the reference frontsteal-render compares lagging frames to.
// A new view id (the update number) is asked for only when the camera or the tolerance changes; a still camera
// costs no tessellation.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/id_range.hpp"
#include "render/greedy_pipeline.hpp"
#include "tessellate/camera.hpp"
#include "tessellate/model.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::render {

struct LiveCounters {
  std::string scheduler;  // the scheduler of the newest frame
  std::uint64_t tessellation_frames = 0;
  std::uint64_t steals = 0;  // successful steals, all frames (schedulers that steal; else 0)
  std::uint64_t last_frame_steals = 0;
  double last_frame_ms = 0;  // wall time of the newest tessellation frame
  std::uint64_t driver_waits = 0;
  std::uint64_t inconsistencies = 0;    // surface tessellations that failed their own audit
  std::uint64_t last_frame_remade = 0;  // surfaces the newest frame re-tessellated (the rest reused)
};

class LiveGreedy {
 public:
  // The schedulers the viewer may switch between: the registry's exactly-once ones (an at-least-once scheduler,
  // stealing/Paper, may run a surface twice, and a component's count-down would then swap it in torn).
  static std::vector<std::string> scheduler_names();

  // Starts the driver thread; throws std::invalid_argument for an unknown scheduler or bad sizes. `reuse`:
  // unchanged surfaces keep their triangles (GreedySession).
  LiveGreedy(const tess::Model& model, WorkerId tessellators, std::uint32_t slots, const std::string& scheduler,
             const tess::TessellationSettings& settings, bool reuse = true);
  ~LiveGreedy();  // stops the driver; call stop_drawing() first, with the context current, if start_drawing() was
  LiveGreedy(const LiveGreedy&) = delete;
  LiveGreedy& operator=(const LiveGreedy&) = delete;

  // Pusher thread, with an OpenGL 3.3 core context current: create / delete the GL objects.
  void start_drawing();
  void stop_drawing();

  // One displayed frame for `camera` (viewport camera.width × camera.height, into the bound framebuffer).
  // With `capture`, reads the drawn image back. Throws std::runtime_error if the driver failed.
  UpdateRecord update(const tess::Camera& camera, Image* capture = nullptr);

  void set_synchronized(bool on) noexcept { synchronized_ = on; }
  bool synchronized() const noexcept { return synchronized_; }
  void set_tolerance(double pixels);  // asks for a new view (re-tessellation)
  double tolerance() const noexcept { return settings_.pixel_tolerance; }
  void set_scheduler(const std::string& name);  // std::invalid_argument if not one of scheduler_names()
  const std::string& scheduler() const noexcept { return scheduler_; }
  WorkerId tessellators() const noexcept { return tessellators_; }
  int updates() const noexcept { return updates_; }
  LiveCounters counters() const;

 private:
  struct Request {
    int view = -1;
    tess::Camera camera;
    tess::TessellationSettings settings;
    std::string scheduler;
  };
  void drive();  // the driver thread
  void ask(const tess::Camera& camera);

  GreedySession session_;
  WorkerId tessellators_;
  std::unique_ptr<GreedyPusher> pusher_;
  // Pusher-thread state.
  bool synchronized_ = false;
  tess::TessellationSettings settings_;
  std::string scheduler_;
  bool view_dirty_ = true;
  tess::Camera last_camera_;
  int updates_ = 0, current_view_ = -1;
  // Shared with the driver, under mutex_.
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Request request_;
  bool stop_ = false;
  int done_view_ = -1;  // the newest view a finished tessellation frame was for
  std::string error_;   // the driver's failure, if any (then it stops)
  LiveCounters counters_;
  std::thread driver_;
};

}  // namespace frontsteal::render
