// frontsteal-view — greedy rendering (paper §5) live in a window: the camera follows the mouse and keys, the
// tessellators (any exactly-once scheduler of the registry) re-tessellate for the newest view, and the pusher
// draws every frame with whatever each component last published, exactly as frontsteal-render does headless
// (render/live_greedy.hpp, render/greedy_pipeline.hpp: the same code). GLFW window, Dear ImGui overlay; this
// file only parses the options, loads the scene and installs the signal handler (render/view_window.hpp runs it).
//
// Exit status: 0 on window close, Escape, --frames or Ctrl-C (SIGINT / SIGTERM set a flag the loop checks; GL and
// GLFW are torn down in order); 2 on a usage error (CLI11); 3 when there is no display or no OpenGL 3.3 context.
#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <tuple>

#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "render/live_greedy.hpp"
#include "render/render_scene.hpp"
#include "render/view_controls.hpp"
#include "render/view_window.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;
namespace report = frontsteal::report;

namespace {

constexpr std::string_view kProgram = "frontsteal-view";

constexpr const char* kAbout =
    R"(Greedy rendering (paper §5) live in a window: tessellators (the stealing scheduler, or any exactly-once
scheduler of the registry) re-tessellate the scene for the newest view while the pusher draws every frame with
whatever each component last published. Same pusher and tessellation code as frontsteal-render. An overlay shows
the update rate, the tessellation rate, the lag and the steals per tessellation frame. Exit status: 0 on window
close, Escape, --frames or Ctrl-C; 2 on a usage error; 3 without a display or an OpenGL 3.3 context.)";

rd::ViewOptions parse(int argc, char** argv) {
  rd::ViewOptions o;
  o.tessellators = std::max(2u, std::thread::hardware_concurrency()) - 1;  // 0 means unknown: one
  std::string size = "960x600";
  bool no_overlay = false;
  report::CommandLine cli(std::string(kProgram), kAbout, std::string("keys:\n") + rd::kViewKeys);
  cli.option("--scene", o.scene, "teapot, teacup, teaspoon, plant:<N>[:seed] or a model file");
  cli.option("--size", size, "window size")->check(report::size_validator());
  cli.option("--tolerance", o.tolerance, "screen-space tessellation tolerance, pixels")->check(CLI::Range(0.05, 100.0));
  cli.option("--tessellators", o.tessellators, "tessellator threads (default: cores - 1, at least 1)")
      ->check(CLI::Range(1u, 256u));
  cli.option("--scheduler", o.scheduler, "scheduler of the tessellators (the registry's exactly-once ones)")
      ->check(CLI::IsMember(rd::LiveGreedy::scheduler_names()));
  cli.flag("--synchronized", o.synchronized, "start synchronized (T toggles)");
  cli.flag("--no-overlay", no_overlay, "start with the overlay hidden (H toggles)");
  bool no_reuse = false;
  cli.flag("--no-reuse", no_reuse,
           "tessellate every surface every frame; by default a surface whose steps and trim polylines did not "
           "change keeps its triangles (the same bytes), as the paper's renderer does");
  cli.option("--rate", o.rate, "at most R frames per second; 0: as fast as it can")->check(CLI::Range(0.0, 10000.0));
  cli.option("--screenshot", o.screenshot, "where P writes the window (PNG); with --frames, also after the last frame");
  cli.option("--frames", o.frames, "exit after N frames (tests, screenshots); 0: run on")
      ->check(CLI::Range(0, 100'000'000));
  cli.parse(argc, argv);  // --help: exit 0; a mistake: exit 2, as every frontsteal command
  std::tie(o.width, o.height) = report::parse_size(size);
  o.overlay = !no_overlay;
  o.reuse = !no_reuse;
  return o;
}

// Ctrl-C: only a flag (async-signal-safe); the frame loop sees it and tears everything down in order.
volatile std::sig_atomic_t g_interrupted = 0;
void on_signal(int) { g_interrupted = 1; }

}  // namespace

int main(int argc, char** argv) {
  const rd::ViewOptions o = parse(argc, argv);
  const std::optional<ts::Model> loaded = rd::load_render_scene_or_report(kProgram, o.scene, FRONTSTEAL_DATA_DIR);
  if (!loaded) return 2;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  return rd::run_view(*loaded, o, g_interrupted);
}
