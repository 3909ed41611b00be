// view_controls.hpp — frontsteal-view's input: GLFW key, character, mouse and scroll callbacks that step the
// camera (view_camera.hpp: discrete steps, so a key sequence gives the same camera on any machine) and switch
// the live pipeline's mode, scheduler and tolerance (live_greedy.hpp). The key table, once, for --help and the
// overlay.
//
// The callbacks run inside glfwPollEvents on the main (pusher) thread, the only thread that touches LiveGreedy's
// pusher-side settings, so nothing is locked.
#pragma once

#include <string>
#include <vector>

#include "render/live_greedy.hpp"
#include "render/view_camera.hpp"
#include "tessellate/culling.hpp"

struct GLFWwindow;

namespace frontsteal::render {

extern const char* const kViewKeys;  // one line per key: "  key   action"

struct ViewControls {
  ViewControls(const tess::Box& box, LiveGreedy& live_greedy)
      : camera(box), live(live_greedy), schedulers(LiveGreedy::scheduler_names()) {}
  ViewCamera camera;
  LiveGreedy& live;
  std::vector<std::string> schedulers;  // what C and V cycle through
  bool overlay = true;                  // H
  bool keys_shown = false;              // K: the overlay starts with the figures only, keys folded
  bool screenshot = false;              // P: the loop writes one and clears this
  bool dragging = false;
  double last_x = 0, last_y = 0;
  std::string message;  // the last action, for the overlay
};

// Installs the callbacks on `window` (call before ImGui's GLFW backend, which chains to the callbacks it finds);
// `controls` must outlive the window's event processing. Mouse input the overlay wants (ImGui) is left to it.
void install_controls(GLFWwindow* window, ViewControls& controls);

}  // namespace frontsteal::render
