// view_window.cpp — frontsteal-view's window and frame loop (view_window.hpp).
#define GL_GLEXT_PROTOTYPES 1
#define GLFW_INCLUDE_GLEXT
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "render/view_window.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "render/image.hpp"
#include "render/live_greedy.hpp"
#include "render/triangle_renderer.hpp"
#include "render/view_controls.hpp"
#include "render/view_overlay.hpp"
#include "tessellate/camera_path.hpp"

namespace frontsteal::render {

namespace {

constexpr const char* kProgram = "frontsteal-view";
using Clock = std::chrono::steady_clock;

std::string g_glfw_error;  // the latest GLFW error, for the exit-3 message
void on_glfw_error(int code, const char* text) {
  g_glfw_error = "GLFW error " + std::to_string(code) + ": " + (text ? text : "?");
}

bool set(const char* variable) {
  const char* v = std::getenv(variable);
  return v != nullptr && *v != '\0';
}

// The window with its context current, or nullptr after saying why (GLFW is then terminated).
GLFWwindow* open_window(const ViewOptions& o) {
  if (!set("DISPLAY") && !set("WAYLAND_DISPLAY")) {
    std::cerr << kProgram << ": no display: neither DISPLAY nor WAYLAND_DISPLAY is set. Run it in a desktop session, "
              << "or under Xvfb (xvfb-run -a -s \"-screen 0 1280x800x24\" frontsteal-view ...); "
              << "frontsteal-render renders without a display.\n";
    return nullptr;
  }
  glfwSetErrorCallback(on_glfw_error);
  if (glfwInit() != GLFW_TRUE) {
    std::cerr << kProgram << ": no display: GLFW could not start (" << g_glfw_error << ")\n";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "frontsteal-view", nullptr, nullptr);
  if (window == nullptr) {
    std::cerr << kProgram << ": no OpenGL 3.3 core window on this display (" << g_glfw_error << ")\n";
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(o.rate > 0 ? 0 : 1);  // --rate paces; with 0, the display's refresh (where it has one)
  return window;
}

void start_imgui(GLFWwindow* window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the callbacks install_controls set
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

void stop_imgui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

class FrameLoop {
 public:
  FrameLoop(GLFWwindow* window, const ViewOptions& o, const tess::Model& model, LiveGreedy& live,
            ViewControls& controls)
      : window_(window), o_(o), live_(live), controls_(controls) {
    text_.title = o.scene + ": " + std::to_string(model.surfaces.size()) + " surfaces";
    text_.renderer = gl_string(GL_RENDERER) + ", OpenGL " + gl_string(GL_VERSION);
  }
  const std::string& renderer() const { return text_.renderer; }

  // Until closed, --frames or interrupted; returns why it stopped.
  std::string run(const volatile std::sig_atomic_t& interrupted) {
    const auto period =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o_.rate > 0 ? 1.0 / o_.rate : 0.0));
    auto next_frame = Clock::now();
    for (int frame = 0;; ++frame) {
      if (interrupted) return "interrupted (SIGINT/SIGTERM)";
      if (glfwWindowShouldClose(window_)) return "window closed";
      if (o_.frames > 0 && frame >= o_.frames) return "--frames " + std::to_string(o_.frames);
      glfwPollEvents();
      draw(o_.frames > 0 && frame + 1 == o_.frames && !o_.screenshot.empty());
      glfwSwapBuffers(window_);
      if (o_.rate > 0) {  // at most --rate frames per second; a late frame is not made up by a burst
        next_frame = std::max(next_frame + period, Clock::now());
        std::this_thread::sleep_until(next_frame);
      }
    }
  }

 private:
  void draw(bool last_screenshot) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    if (fw < 1 || fh < 1) {  // minimized
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      return;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    const tess::Camera cam = controls_.camera.camera(fw, fh);
    const UpdateRecord rec = live_.update(cam);
    rates_.sample(live_.updates(), live_.counters());
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    text_.message = controls_.message;
    overlay_size_ = controls_.overlay ? draw_overlay(text_, live_, rec, rates_, controls_.keys_shown) : OverlaySize{};
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (controls_.screenshot || last_screenshot) screenshot(cam, rec);
  }

  // The window as shown (overlay included unless hidden), before the swap; the camera to stdout.
  void screenshot(const tess::Camera& cam, const UpdateRecord& rec) {
    controls_.screenshot = false;
    char name[64];
    std::snprintf(name, sizeof name, "frontsteal-view-%04d.png", screenshots_++);
    const std::string path = o_.screenshot.empty() ? std::string(name) : o_.screenshot;
    write_png(read_framebuffer(cam.width, cam.height), path);
    std::cout << kProgram << ": screenshot " << path << " update " << rec.update << " camera "
              << ViewCamera::describe(cam) << " tolerance=" << live_.tolerance()
              << " mode=" << (live_.synchronized() ? "synchronized" : "lagging") << " mean_lag=" << rec.mean_lag
              << " overlay=" << (controls_.overlay ? "shown" : "hidden") << " overlay_px=" << overlay_size_.width << 'x'
              << overlay_size_.height << " keys=" << (controls_.keys_shown ? "shown" : "folded") << std::endl;
    controls_.message = "wrote " + path;
  }

  GLFWwindow* window_;
  const ViewOptions& o_;
  LiveGreedy& live_;
  ViewControls& controls_;
  OverlayText text_;
  OverlayRates rates_;
  OverlaySize overlay_size_;  // as drawn this update (0x0 when hidden)
  int screenshots_ = 0;
};

}  // namespace

int run_view(const tess::Model& model, const ViewOptions& o, const volatile std::sig_atomic_t& interrupted) {
  GLFWwindow* window = open_window(o);
  if (window == nullptr) return 3;
  int status = 0;
  {
    tess::TessellationSettings settings;
    settings.pixel_tolerance = o.tolerance;
    LiveGreedy live(model, o.tessellators, 3, o.scheduler, settings, o.reuse);
    live.set_synchronized(o.synchronized);
    ViewControls controls(tess::model_box(model), live);
    controls.overlay = o.overlay;
    install_controls(window, controls);  // before ImGui's backend, which chains to them
    start_imgui(window);
    FrameLoop loop(window, o, model, live, controls);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    std::cout << kProgram << ": " << o.scene << " (" << model.surfaces.size() << " surfaces), " << loop.renderer()
              << ", " << live.scheduler() << " with " << live.tessellators() << " tessellator(s), "
              << (live.synchronized() ? "synchronized" : "lagging") << "; keys in the overlay and in --help\n"
              << kProgram << ": start camera " << ViewCamera::describe(controls.camera.camera(fw, fh)) << std::endl;
    const auto start = Clock::now();
    std::string why;
    try {
      live.start_drawing();
      why = loop.run(interrupted);
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": " << e.what() << '\n';
      why = "failed";
      status = 1;
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const LiveCounters c = live.counters();
    std::cout << kProgram << ": " << why << " after " << live.updates() << " updates in " << seconds << " s ("
              << live.updates() / std::max(seconds, 1e-9) << " updates/s), " << c.tessellation_frames
              << " tessellation frames, " << c.steals << " steals, " << c.inconsistencies
              << " failing surface tessellations" << std::endl;
    if (c.inconsistencies > 0 && status == 0) status = 1;
    // Teardown in order, with the context current: our GL objects, then ImGui's.
    live.stop_drawing();
    stop_imgui();
  }  // the tessellation driver stops here (LiveGreedy's destructor)
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace frontsteal::render
