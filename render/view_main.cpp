// frontsteal-view — greedy rendering (paper §5) live in a window: the camera follows the mouse and keys, the
// tessellators (any exactly-once scheduler of the registry) re-tessellate for the newest view, and the pusher
// draws every frame with whatever each component last published, exactly as frontsteal-render does headless
// (render/live_greedy.hpp, render/greedy_pipeline.hpp: the same code). GLFW window, Dear ImGui overlay.
//
// Exit status: 0 on window close, Escape, --frames or Ctrl-C (SIGINT / SIGTERM set a flag the loop checks; GL and
// GLFW are torn down in order); 2 on a usage error (CLI11); 3 when there is no display or no OpenGL 3.3 context.
#define GL_GLEXT_PROTOTYPES 1
#define GLFW_INCLUDE_GLEXT
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <CLI/CLI.hpp>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <thread>

#include "core/cli_args.hpp"
#include "render/image.hpp"
#include "render/live_greedy.hpp"
#include "render/render_scene.hpp"
#include "render/triangle_renderer.hpp"
#include "render/view_camera.hpp"
#include "tessellate/camera_path.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

constexpr std::string_view kProgram = "frontsteal-view";

// The keys, once: --help prints them and the overlay shows them.
constexpr const char* kKeys = R"(  mouse drag (left)    orbit around the target
  mouse wheel, Z / X   zoom in / out
  W A S D, arrows      walk forward / left / back / right (the target moves with the eye)
  R / F                walk up / down
  T                    toggle lagging (pusher never waits) / synchronized (waits for its own view)
  C                    next scheduler (the registry's exactly-once ones)
  V                    next stealing policy (stealing/<Policy>)
  + / -                tessellation tolerance x1.25 / /1.25 (pixels; larger is coarser)
  H                    hide / show this overlay
  P                    screenshot (to --screenshot FILE, else frontsteal-view-NNNN.png), camera to stdout
  0, Home              reset the camera
  Escape, Q            quit
)";

constexpr const char* kAbout = R"(Greedy rendering (paper §5) live in a window: tessellators (the stealing scheduler, or any exactly-once
scheduler of the registry) re-tessellate the scene for the newest view while the pusher draws every frame with
whatever each component last published. Same pusher and tessellation code as frontsteal-render. An overlay shows
the update rate, the tessellation rate, the lag and the steals per tessellation frame. Exit status: 0 on window
close, Escape, --frames or Ctrl-C; 2 on a usage error; 3 without a display or an OpenGL 3.3 context.)";

struct Options {
  std::string scene = "teapot";
  int width = 960, height = 600;
  double tolerance = 1.0;
  frontsteal::WorkerId tessellators = 1;
  std::string scheduler = "stealing/Fenced";
  bool synchronized = false, overlay = true;
  double rate = 60;
  std::string screenshot;
  int frames = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  o.tessellators = std::max(1u, std::thread::hardware_concurrency() - 1);
  std::string size = "960x600";
  bool no_overlay = false;
  CLI::App app(kAbout, std::string(kProgram));
  app.footer(std::string("keys:\n") + kKeys);
  app.add_option("--scene", o.scene, "teapot, teacup, teaspoon, plant:<N>[:seed] or a model file")->capture_default_str();
  app.add_option("--size", size, "window size WxH")->capture_default_str();
  app.add_option("--tolerance", o.tolerance, "screen-space tessellation tolerance, pixels")
      ->check(CLI::Range(0.05, 100.0))->capture_default_str();
  app.add_option("--tessellators", o.tessellators, "tessellator threads (default: cores - 1, at least 1)")
      ->check(CLI::Range(1u, 256u))->capture_default_str();
  app.add_option("--scheduler", o.scheduler, "scheduler of the tessellators (the registry's exactly-once ones)")
      ->check(CLI::IsMember(rd::LiveGreedy::scheduler_names()))->capture_default_str();
  app.add_flag("--synchronized", o.synchronized, "start synchronized (T toggles)");
  app.add_flag("--no-overlay", no_overlay, "start with the overlay hidden (H toggles)");
  app.add_option("--rate", o.rate, "at most R frames per second; 0: as fast as it can")
      ->check(CLI::Range(0.0, 10000.0))->capture_default_str();
  app.add_option("--screenshot", o.screenshot, "where P writes the window (PNG); with --frames, also after the last frame");
  app.add_option("--frames", o.frames, "exit after N frames (tests, screenshots); 0: run on")
      ->check(CLI::Range(0, 100'000'000))->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    std::exit(0);
  } catch (const CLI::ParseError& e) {
    frontsteal::cli::usage_error(kProgram, e.what());  // exit 2, as every frontsteal command
  }
  const frontsteal::cli::Size window = frontsteal::cli::parse_size(kProgram, "--size", size, 64, 8192);
  o.width = window.width;
  o.height = window.height;
  o.overlay = !no_overlay;
  return o;
}

// Ctrl-C: only a flag (async-signal-safe); the loop sees it and tears everything down in order.
volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

std::string g_glfw_error;  // the latest GLFW error, for the exit-3 message
void on_glfw_error(int code, const char* text) {
  g_glfw_error = "GLFW error " + std::to_string(code) + ": " + (text ? text : "?");
}

// What the input callbacks change; the loop applies it. Callbacks run inside glfwPollEvents on the main
// (pusher) thread, so no locking.
struct ViewState {
  explicit ViewState(const ts::Box& box) : camera(box) {}
  rd::ViewCamera camera;
  rd::LiveGreedy* live = nullptr;
  std::vector<std::string> schedulers;
  bool overlay = true;
  bool screenshot = false;
  bool dragging = false;
  double last_x = 0, last_y = 0;
  std::string message;  // last action, shown in the overlay
};

ViewState& state_of(GLFWwindow* w) { return *static_cast<ViewState*>(glfwGetWindowUserPointer(w)); }

void next_scheduler(ViewState& s, bool stealing_only) {
  const auto at = std::find(s.schedulers.begin(), s.schedulers.end(), s.live->scheduler());
  std::size_t i = at == s.schedulers.end() ? 0 : static_cast<std::size_t>(at - s.schedulers.begin());
  for (std::size_t k = 0; k < s.schedulers.size(); ++k) {
    i = (i + 1) % s.schedulers.size();
    if (!stealing_only || s.schedulers[i].rfind("stealing/", 0) == 0) break;
  }
  s.live->set_scheduler(s.schedulers[i]);
  s.message = "scheduler " + s.schedulers[i];
}

void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_RELEASE) return;
  ViewState& s = state_of(w);
  switch (key) {
    case GLFW_KEY_W: case GLFW_KEY_UP: s.camera.walk(1, 0, 0); break;
    case GLFW_KEY_S: case GLFW_KEY_DOWN: s.camera.walk(-1, 0, 0); break;
    case GLFW_KEY_A: case GLFW_KEY_LEFT: s.camera.walk(0, -1, 0); break;
    case GLFW_KEY_D: case GLFW_KEY_RIGHT: s.camera.walk(0, 1, 0); break;
    case GLFW_KEY_R: s.camera.walk(0, 0, 1); break;
    case GLFW_KEY_F: s.camera.walk(0, 0, -1); break;
    case GLFW_KEY_Z: s.camera.zoom(1); break;
    case GLFW_KEY_X: s.camera.zoom(-1); break;
    case GLFW_KEY_0: case GLFW_KEY_HOME: s.camera.reset(); s.message = "camera reset"; break;
    case GLFW_KEY_T:
      if (action != GLFW_PRESS) break;  // a held key would flicker between the modes
      s.live->set_synchronized(!s.live->synchronized());
      s.message = s.live->synchronized() ? "synchronized" : "lagging";
      break;
    case GLFW_KEY_C: if (action == GLFW_PRESS) next_scheduler(s, false); break;
    case GLFW_KEY_V: if (action == GLFW_PRESS) next_scheduler(s, true); break;
    case GLFW_KEY_H: if (action == GLFW_PRESS) s.overlay = !s.overlay; break;
    case GLFW_KEY_P: if (action == GLFW_PRESS) s.screenshot = true; break;
    case GLFW_KEY_ESCAPE: case GLFW_KEY_Q: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
    default: break;
  }
}

// + and - as characters, so they work on any keyboard layout and on the keypad.
void on_char(GLFWwindow* w, unsigned codepoint) {
  ViewState& s = state_of(w);
  double t = s.live->tolerance();
  if (codepoint == '+' || codepoint == '=') t *= 1.25;
  else if (codepoint == '-' || codepoint == '_') t /= 1.25;
  else return;
  t = std::clamp(t, 0.05, 100.0);
  s.live->set_tolerance(t);
  char text[64];
  std::snprintf(text, sizeof text, "tolerance %.3g px", t);
  s.message = text;
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
  ViewState& s = state_of(w);
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  s.dragging = action == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse;
  glfwGetCursorPos(w, &s.last_x, &s.last_y);
}

void on_cursor(GLFWwindow* w, double x, double y) {
  ViewState& s = state_of(w);
  if (s.dragging) s.camera.orbit(x - s.last_x, y - s.last_y);
  s.last_x = x;
  s.last_y = y;
}

void on_scroll(GLFWwindow* w, double, double dy) {
  if (!ImGui::GetIO().WantCaptureMouse) state_of(w).camera.zoom(dy);
}

// Rates over the last half second or more (the overlay must not flicker with every frame).
struct Rates {
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  int updates0 = 0;
  std::uint64_t frames0 = 0, steals0 = 0;
  double updates_per_s = 0, frames_per_s = 0, steals_per_frame = 0;
  void sample(int updates, const rd::LiveCounters& c) {
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - t0).count();
    if (dt < 0.5) return;
    updates_per_s = (updates - updates0) / dt;
    frames_per_s = static_cast<double>(c.tessellation_frames - frames0) / dt;
    if (c.tessellation_frames > frames0) {
      steals_per_frame = static_cast<double>(c.steals - steals0) / static_cast<double>(c.tessellation_frames - frames0);
    }
    t0 = now;
    updates0 = updates;
    frames0 = c.tessellation_frames;
    steals0 = c.steals;
  }
};

void draw_overlay(const Options& o, const ts::Model& model, const std::string& renderer, rd::LiveGreedy& live,
                  const rd::UpdateRecord& rec, const Rates& rates, const ViewState& s) {
  const rd::LiveCounters c = live.counters();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.7f);
  ImGui::Begin("frontsteal-view", nullptr,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  ImGui::Text("%s: %zu surfaces", o.scene.c_str(), model.surfaces.size());
  ImGui::TextUnformatted(renderer.c_str());
  ImGui::Separator();
  ImGui::Text("mode        %s", live.synchronized() ? "synchronized (pusher waits)" : "lagging (pusher never waits)");
  ImGui::Text("scheduler   %s, %u tessellator(s)", live.scheduler().c_str(), live.tessellators());
  ImGui::Text("tolerance   %.3g px", live.tolerance());
  ImGui::Text("updates     %.1f /s   (draw %.2f ms, %llu triangles)", rates.updates_per_s, rec.draw_ms,
              static_cast<unsigned long long>(rec.triangles));
  ImGui::Text("tessellation %.1f frames/s   (last %.1f ms%s)", rates.frames_per_s, c.last_frame_ms,
              rates.frames_per_s == 0 && rec.max_lag == 0 ? ", idle: the view is unchanged" : "");
  ImGui::Text("lag         mean %.2f, max %d updates", rec.mean_lag, rec.max_lag);
  ImGui::Text("steals      %.1f per frame (last frame %llu)", rates.steals_per_frame,
              static_cast<unsigned long long>(c.last_frame_steals));
  if (c.inconsistencies > 0) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "AUDIT: %llu failing surface tessellations",
                                                static_cast<unsigned long long>(c.inconsistencies));
  if (!s.message.empty()) ImGui::Text("> %s", s.message.c_str());
  ImGui::Separator();
  ImGui::TextUnformatted(kKeys);
  ImGui::End();
}

std::string gl_string(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const std::optional<ts::Model> loaded = rd::load_render_scene_or_report(kProgram, o.scene, FRONTSTEAL_DATA_DIR);
  if (!loaded) return 2;
  const ts::Model& model = *loaded;

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0')) {
    std::cerr << kProgram << ": no display: neither DISPLAY nor WAYLAND_DISPLAY is set. Run it in a desktop session, "
              << "or under Xvfb (xvfb-run -a -s \"-screen 0 1280x800x24\" frontsteal-view ...); "
              << "frontsteal-render renders without a display.\n";
    return 3;
  }
  glfwSetErrorCallback(on_glfw_error);
  if (glfwInit() != GLFW_TRUE) {
    std::cerr << kProgram << ": no display: GLFW could not start (" << g_glfw_error << ")\n";
    return 3;
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
    return 3;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(o.rate > 0 ? 0 : 1);  // --rate paces; with 0, the display's refresh (where it has one)

  int status = 0;
  std::string why = "window closed";
  {
    ViewState state(ts::model_box(model));
    ts::TessellationSettings settings;
    settings.pixel_tolerance = o.tolerance;
    rd::LiveGreedy live(model, o.tessellators, 3, o.scheduler, settings);
    live.set_synchronized(o.synchronized);
    state.live = &live;
    state.schedulers = rd::LiveGreedy::scheduler_names();
    state.overlay = o.overlay;
    glfwSetWindowUserPointer(window, &state);
    // Ours first: ImGui's backend chains to the callbacks it finds installed.
    glfwSetKeyCallback(window, on_key);
    glfwSetCharCallback(window, on_char);
    glfwSetMouseButtonCallback(window, on_mouse_button);
    glfwSetCursorPosCallback(window, on_cursor);
    glfwSetScrollCallback(window, on_scroll);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    const std::string renderer = gl_string(GL_RENDERER) + ", OpenGL " + gl_string(GL_VERSION);
    std::cout << kProgram << ": " << o.scene << " (" << model.surfaces.size() << " surfaces), " << renderer << ", "
              << live.scheduler() << " with " << live.tessellators() << " tessellator(s), "
              << (live.synchronized() ? "synchronized" : "lagging") << "; keys in the overlay and in --help" << std::endl;
    {
      int fw = 0, fh = 0;
      glfwGetFramebufferSize(window, &fw, &fh);
      std::cout << kProgram << ": start camera " << rd::ViewCamera::describe(state.camera.camera(fw, fh)) << std::endl;
    }
    Rates rates;
    int screenshots = 0;
    const auto start = std::chrono::steady_clock::now();
    const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(o.rate > 0 ? 1.0 / o.rate : 0.0));
    auto next_frame = start;
    try {
      live.start_drawing();
      for (int frame = 0;; ++frame) {
        if (g_interrupted) {
          why = "interrupted (SIGINT/SIGTERM)";
          break;
        }
        if (glfwWindowShouldClose(window)) break;
        if (o.frames > 0 && frame >= o.frames) {
          why = "--frames " + std::to_string(o.frames);
          break;
        }
        glfwPollEvents();
        int fw = 0, fh = 0;
        glfwGetFramebufferSize(window, &fw, &fh);
        if (fw < 1 || fh < 1) {  // minimized
          std::this_thread::sleep_for(std::chrono::milliseconds(50));
          continue;
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fw, fh);
        const ts::Camera cam = state.camera.camera(fw, fh);
        const rd::UpdateRecord rec = live.update(cam);
        rates.sample(live.updates(), live.counters());
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (state.overlay) draw_overlay(o, model, renderer, live, rec, rates, state);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        const bool last = o.frames > 0 && frame + 1 == o.frames && !o.screenshot.empty();
        if (state.screenshot || last) {
          state.screenshot = false;
          char name[64];
          std::snprintf(name, sizeof name, "frontsteal-view-%04d.png", screenshots);
          const std::string path = o.screenshot.empty() ? std::string(name) : o.screenshot;
          rd::write_png(rd::read_framebuffer(fw, fh), path);
          ++screenshots;
          std::cout << kProgram << ": screenshot " << path << " update " << rec.update << " camera "
                    << rd::ViewCamera::describe(cam) << " tolerance=" << live.tolerance()
                    << " mode=" << (live.synchronized() ? "synchronized" : "lagging") << " mean_lag=" << rec.mean_lag
                    << " overlay=" << (state.overlay ? "shown" : "hidden") << std::endl;
          state.message = "wrote " + path;
        }
        glfwSwapBuffers(window);
        if (o.rate > 0) {  // at most --rate frames per second; a late frame is not made up by a burst
          next_frame = std::max(next_frame + period, std::chrono::steady_clock::now());
          std::this_thread::sleep_until(next_frame);
        }
      }
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": " << e.what() << '\n';
      why = "failed";
      status = 1;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const rd::LiveCounters c = live.counters();
    std::cout << kProgram << ": " << why << " after " << live.updates() << " updates in " << seconds << " s ("
              << live.updates() / std::max(seconds, 1e-9) << " updates/s), " << c.tessellation_frames
              << " tessellation frames, " << c.steals << " steals, " << c.inconsistencies
              << " failing surface tessellations" << std::endl;
    if (c.inconsistencies > 0 && status == 0) status = 1;
    // Teardown in order, with the context current: our GL objects, ImGui's, then the window and GLFW.
    live.stop_drawing();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }  // the driver thread stops here (LiveGreedy's destructor)
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}
