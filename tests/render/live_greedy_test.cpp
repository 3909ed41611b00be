// LiveGreedy (render/live_greedy.hpp), headless: the viewer's pipeline without a window. Synchronized updates are
// drawn for their own view (lag 0) and look like render_synchronized of that camera; lagging updates never wait
// and catch up once the camera stops; switching schedulers keeps tessellating; an at-least-once scheduler is
// refused; the camera steps are deterministic.
#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>

#include <catch2/catch.hpp>

#include "render/headless_gl.hpp"
#include "render/live_greedy.hpp"
#include "render/render_scene.hpp"
#include "render/triangle_renderer.hpp"
#include "render/view_camera.hpp"
#include "tessellate/camera_path.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

// The teapot, its camera and a 160 x 96 headless context current on this thread for the test's lifetime.
struct Headless {
  ts::Model model = rd::load_render_scene("teapot", FRONTSTEAL_DATA_DIR);
  rd::ViewCamera view{ts::model_box(model)};
  rd::HeadlessGL gl{160, 96};
  Headless() { gl.make_current(); }
  ~Headless() { gl.release(); }
  ts::Camera camera() const { return view.camera(160, 96); }
};

}  // namespace

TEST_CASE("live greedy rendering: synchronized updates show their own view") {
  Headless h;
  const ts::Model& m = h.model;
  rd::ViewCamera& view = h.view;
  {
    rd::LiveGreedy live(m, 1, 3, "stealing/Fenced", {});
    live.set_synchronized(true);
    live.start_drawing();
    for (int k = 0; k < 4; ++k) {
      view.zoom(1);
      view.orbit(15, 0);
      const ts::Camera cam = view.camera(160, 96);
      rd::Image image;
      const rd::UpdateRecord rec = live.update(cam, &image);
      CHECK(rec.max_lag == 0);
      CHECK(rec.triangles > 0);
      const rd::Image reference = rd::render_synchronized(m, cam, {});
      CHECK(rd::coverage_iou(image, reference, rd::TriangleRenderer::kBackground) > 0.99);
    }
    // Negative control: the last image against the view before the last step must not match as well.
    rd::Image image;
    live.update(view.camera(160, 96), &image);
    rd::ViewCamera earlier = view;
    earlier.zoom(-1);
    earlier.orbit(-15, 0);
    CHECK(rd::coverage_iou(image, rd::render_synchronized(m, earlier.camera(160, 96), {}),
                           rd::TriangleRenderer::kBackground) < 0.9);
    CHECK(live.counters().tessellation_frames >= 4);
    CHECK(live.counters().inconsistencies == 0);
    live.stop_drawing();
  }
}

TEST_CASE("live greedy rendering: lagging updates catch up when the camera stops, on every scheduler") {
  Headless h;
  {
    rd::LiveGreedy live(h.model, 2, 3, "stealing/Fenced", {});
    live.start_drawing();
    const auto names = rd::LiveGreedy::scheduler_names();
    REQUIRE(std::find(names.begin(), names.end(), "stealing/Paper") == names.end());  // at-least-once: left out
    CHECK_THROWS_AS(live.set_scheduler("stealing/Paper"), std::invalid_argument);
    for (const std::string& name : names) {  // every scheduler the viewer's C key cycles through
      INFO(name);
      live.set_scheduler(name);
      h.view.orbit(20, 5);
      const ts::Camera cam = h.camera();
      rd::UpdateRecord rec = live.update(cam);  // may show older views: never waits
      // The camera stands still: within a generous bound the pusher draws the current view everywhere.
      for (int k = 0; k < 20000 && !(rec.max_lag == 0 && rec.triangles > 0); ++k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        rec = live.update(cam);
      }
      CHECK(rec.max_lag == 0);
      // Components are published inside the frame, the counters after it: wait for them too (bounded).
      for (int k = 0; k < 20000 && live.counters().scheduler != name; ++k)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      CHECK(live.counters().scheduler == name);
    }
    live.stop_drawing();
  }
}

TEST_CASE("the viewer's camera is a pure function of its steps") {
  const ts::Model m = rd::load_render_scene("teapot", FRONTSTEAL_DATA_DIR);
  rd::ViewCamera a(ts::model_box(m)), b(ts::model_box(m));
  for (rd::ViewCamera* v : {&a, &b}) {
    v->zoom(2);
    v->walk(1, 1, 0);
    v->orbit(-30, 12);
  }
  CHECK(rd::ViewCamera::describe(a.camera(320, 240)) == rd::ViewCamera::describe(b.camera(320, 240)));
  a.reset();
  // The start is frame 0 of the orbit path of frontsteal-render.
  const ts::Camera start = a.camera(320, 240);
  const ts::Camera path = ts::camera_on(ts::CameraPathKind::orbit, ts::model_box(m), 0, 10, 320, 240);
  CHECK(glm::length(start.eye - path.eye) < 1e-9 * glm::length(path.eye));
  CHECK(glm::length(start.target - path.target) < 1e-9 * (1 + glm::length(path.target)));
}
