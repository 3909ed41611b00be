// view_controls.cpp — frontsteal-view's input callbacks (view_controls.hpp).
#include "render/view_controls.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace frontsteal::render {

const char* const kViewKeys = R"(  mouse drag (left)    orbit around the target
  mouse wheel, Z / X   zoom in / out
  W A S D, arrows      walk forward / left / back / right (the target moves with the eye)
  R / F                walk up / down
  T                    toggle lagging (pusher never waits) / synchronized (waits for its own view)
  C                    next scheduler (the registry's exactly-once ones)
  V                    next stealing policy (stealing/<Policy>)
  + / -                tessellation tolerance x1.25 / /1.25 (pixels; larger is coarser)
  H                    hide / show this overlay
  K                    show / fold this key list
  P                    screenshot (to --screenshot FILE, else frontsteal-view-NNNN.png), camera to stdout
  0, Home              reset the camera
  Escape, Q            quit
)";

namespace {

ViewControls& controls_of(GLFWwindow* w) { return *static_cast<ViewControls*>(glfwGetWindowUserPointer(w)); }

void next_scheduler(ViewControls& s, bool stealing_only) {
  const auto at = std::find(s.schedulers.begin(), s.schedulers.end(), s.live.scheduler());
  std::size_t i = at == s.schedulers.end() ? 0 : static_cast<std::size_t>(at - s.schedulers.begin());
  for (std::size_t k = 0; k < s.schedulers.size(); ++k) {
    i = (i + 1) % s.schedulers.size();
    if (!stealing_only || s.schedulers[i].rfind("stealing/", 0) == 0) break;
  }
  s.live.set_scheduler(s.schedulers[i]);
  s.message = "scheduler " + s.schedulers[i];
}

void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE) return;
  ViewControls& s = controls_of(w);
  const bool press = action == GLFW_PRESS;  // toggles ignore auto-repeat: a held key would flicker
  switch (key) {
    case GLFW_KEY_W:
    case GLFW_KEY_UP: s.camera.walk(1, 0, 0); break;
    case GLFW_KEY_S:
    case GLFW_KEY_DOWN: s.camera.walk(-1, 0, 0); break;
    case GLFW_KEY_A:
    case GLFW_KEY_LEFT: s.camera.walk(0, -1, 0); break;
    case GLFW_KEY_D:
    case GLFW_KEY_RIGHT: s.camera.walk(0, 1, 0); break;
    case GLFW_KEY_R: s.camera.walk(0, 0, 1); break;
    case GLFW_KEY_F: s.camera.walk(0, 0, -1); break;
    case GLFW_KEY_Z: s.camera.zoom(1); break;
    case GLFW_KEY_X: s.camera.zoom(-1); break;
    case GLFW_KEY_0:
    case GLFW_KEY_HOME:
      s.camera.reset();
      s.message = "camera reset";
      break;
    case GLFW_KEY_T:
      if (!press) break;
      s.live.set_synchronized(!s.live.synchronized());
      s.message = s.live.synchronized() ? "synchronized" : "lagging";
      break;
    case GLFW_KEY_C:
      if (press) next_scheduler(s, false);
      break;
    case GLFW_KEY_V:
      if (press) next_scheduler(s, true);
      break;
    case GLFW_KEY_H:
      if (press) s.overlay = !s.overlay;
      break;
    case GLFW_KEY_K:
      if (press) s.keys_shown = !s.keys_shown;
      break;
    case GLFW_KEY_P:
      if (press) s.screenshot = true;
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    default: break;
  }
}

// + and - as characters, so they work on any keyboard layout and on the keypad.
void on_char(GLFWwindow* w, unsigned codepoint) {
  ViewControls& s = controls_of(w);
  double t = s.live.tolerance();
  if (codepoint == '+' || codepoint == '=')
    t *= 1.25;
  else if (codepoint == '-' || codepoint == '_')
    t /= 1.25;
  else
    return;
  t = std::clamp(t, 0.05, 100.0);
  s.live.set_tolerance(t);
  char text[64];
  std::snprintf(text, sizeof text, "tolerance %.3g px", t);
  s.message = text;
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
  ViewControls& s = controls_of(w);
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  // The drag starts at the position of the last motion event (not a query of the pointer now, which may be
  // ahead of the events not yet handled): the orbit is the sum of the event deltas, the same on every run.
  s.dragging = action == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse;
}

void on_cursor(GLFWwindow* w, double x, double y) {
  ViewControls& s = controls_of(w);
  if (s.dragging) s.camera.orbit(x - s.last_x, y - s.last_y);
  s.last_x = x;
  s.last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  if (!ImGui::GetIO().WantCaptureMouse) controls_of(w).camera.zoom(dy);
}

}  // namespace

void install_controls(GLFWwindow* window, ViewControls& controls) {
  glfwSetWindowUserPointer(window, &controls);
  glfwSetKeyCallback(window, on_key);
  glfwSetCharCallback(window, on_char);
  glfwSetMouseButtonCallback(window, on_mouse_button);
  glfwSetCursorPosCallback(window, on_cursor);
  glfwSetScrollCallback(window, on_scroll);
}

}  // namespace frontsteal::render
