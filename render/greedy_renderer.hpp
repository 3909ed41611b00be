// greedy_renderer.hpp — greedy rendering (paper §5): a pusher that draws at the display rate and never waits,
// tessellators that lag behind it, and the per-component atomic swap of triangle lists between them.
//
// Roles and threads (multi-threaded mode):
//   pusher        one thread owning the OpenGL context (or, with the null renderer, none). Update u: the camera
//                 of path frame u, begin_update, read ComponentTris(c) once per component (a slot of
//                 core/component_publication.hpp), upload it if it changed since the last update, draw every
//                 component, end_update. It never waits for tessellators.
//   tessellators  P workers of the stealing scheduler (Fenced). Each frame reads the pusher's current path frame
//                 (the "current view matrix") at its start, tessellates every surface into its component's back
//                 slot; the worker that finishes a component's last surface swaps it in (§5.2).
//   driver        the calling thread: between frames, picks back slots no pusher update can still be reading.
// Lag of component c at update u = u − the path frame c's displayed triangles were tessellated for (Table 2's
// "lag", in frames). Cracks: components swap independently, so while the view moves a crack can open between
// two components tessellated for different views; inside a component, never (the paper's choice, §5.2).
//
// The pusher's update and the tessellators' per-surface step are render/greedy_pipeline.hpp, shared with the
// interactive viewer (render/live_greedy.hpp, frontsteal-view); this file drives them along a camera path.
//
// Single-threaded mode (§5.3): one thread alternates a draw and a slice of tessellation. With display rate R,
// m triangles drawn and t_p the measured time per drawn triangle, tessellation gets at most 1/R − m·t_p per
// update (and at least one surface, so that it cannot starve).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "render/image.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/model.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::render {

struct GreedyOptions {
  tess::CameraPathKind path = tess::CameraPathKind::walkthrough;
  int updates = 240;          // pusher updates, one path frame each
  double display_rate = 30;   // updates per second the pusher aims at; 0: as fast as it can
  WorkerId tessellators = 1;  // multi-threaded mode
  std::uint32_t slots = 3;    // buffers per component
  int width = 640, height = 360;
  bool null_renderer = false;  // count what would be drawn; no OpenGL
  bool single_thread = false;  // §5.3 time-budget mode
  int samples = 4;             // lagging/synchronized image pairs for PSNR and SSIM (not with the null renderer)
  int png_every = 0;           // also save every K-th update's image (0: none)
  std::string out_dir;         // where images go ("" : none written)
  tess::TessellationSettings settings;
  // Tessellation-bound ("paper-era") mode: every surface is tessellated this many times per tessellation
  // frame, so the tessellators are K times slower than natural while the pusher is not (Table 2's second row).
  int cost_multiplier = 1;
  // Frame-to-frame reuse of unchanged surfaces (tessellate/surface_reuse.hpp); frontsteal-render and -view turn
  // it on unless --no-reuse.
  bool reuse = false;
  std::function<void(const std::string&)> progress;  // a line now and then (may be empty)
};

struct UpdateRecord {
  int update = 0;
  double at_seconds = 0;  // since the run started
  double draw_ms = 0;     // begin_update to end_update, uploads included
  double mean_lag = 0;    // over the components drawn
  int max_lag = 0;
  std::uint64_t triangles = 0;
  std::uint32_t uploads = 0;  // components whose triangles changed since the last update
  double budget_ms = 0;       // single-threaded mode: the tessellation budget of this update
};

struct QualitySample {
  int update = 0;
  double mean_lag = 0;
  double psnr_db = 0;
  double ssim = 0;
  std::string lagging_png, synchronized_png;
};

struct GreedyStats {
  std::string renderer;  // OpenGL vendor/renderer/version, or "null renderer"
  std::string mode;      // "multi-threaded (pusher + P tessellators)" or "single-threaded (§5.3 budget)"
  double seconds = 0;
  int updates = 0;
  std::uint64_t tessellation_frames = 0;
  std::uint64_t surfaces_tessellated = 0;  // surfaces processed (reused ones included)
  std::uint64_t surfaces_remade = 0;       // of those, the ones actually re-tessellated (all without reuse)
  std::uint64_t driver_waits = 0;
  std::uint64_t tessellation_inconsistencies = 0;  // surface tessellations that failed their own audit
  double updates_per_second = 0;
  double tessellations_per_second = 0;  // whole-model tessellation frames per second
  double surfaces_per_second = 0;
  double mean_lag = 0;  // over updates of the per-update mean
  int max_lag = 0;
  double mean_triangles = 0;
  std::vector<UpdateRecord> per_update;
  std::vector<QualitySample> quality;
  std::string colour_plate_png;  // lagging | synchronized side by side, the sample with the largest lag
};

// `model` must have components assigned (tess::assign_components). Throws GraphicsError when OpenGL cannot be
// set up (use null_renderer on machines without EGL), std::invalid_argument for bad options.
GreedyStats run_greedy(const tess::Model& model, const GreedyOptions& options);

// One synchronized frame: every surface tessellated for `camera` and drawn (serially); for tests and references.
Image render_synchronized(const tess::Model& model, const tess::Camera& camera,
                          const tess::TessellationSettings& settings, std::uint64_t* triangles = nullptr);

}  // namespace frontsteal::render
