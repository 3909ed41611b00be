// view_window.hpp — frontsteal-view's window: GLFW (OpenGL 3.3 core), the live greedy pipeline drawing into it
// (live_greedy.hpp), the input (view_controls.hpp), the overlay (view_overlay.hpp), screenshots, and an orderly
// teardown whichever way the loop ends.
#pragma once

#include <csignal>
#include <string>

#include "core/id_range.hpp"
#include "tessellate/model.hpp"

namespace frontsteal::render {

struct ViewOptions {
  std::string scene = "teapot";  // for the overlay and the log
  int width = 960, height = 600;
  double tolerance = 1.0;
  WorkerId tessellators = 1;
  std::string scheduler = "stealing/Fenced";
  bool synchronized = false, overlay = true;
  double rate = 60;        // frames per second at most; 0: unpaced (the display's refresh where there is one)
  std::string screenshot;  // P writes here (else frontsteal-view-NNNN.png); with frames, also after the last
  int frames = 0;          // exit after this many frames; 0: run until closed
  bool reuse = true;       // unchanged surfaces keep their triangles (tessellate/surface_reuse.hpp)
};

// Runs the viewer until the window is closed, Escape, `options.frames` or `interrupted` becomes non-zero (a
// signal handler's flag). Prints a start line, the start camera, one line per screenshot (with the camera, for
// tests to rebuild the view) and a summary on stdout. Returns the exit status: 0 done, 1 failed (or a surface
// tessellation failed its audit), 3 no display or no OpenGL 3.3 core context.
int run_view(const tess::Model& model, const ViewOptions& options, const volatile std::sig_atomic_t& interrupted);

}  // namespace frontsteal::render
