// path_scene.hpp — a scene made ready to be tessellated frame by frame along a camera path: the model, its
// prepared surfaces, one triangle buffer per surface and, per frame, the camera and its frustum.
//
// Why one type: the main job (schedulers/main_job/workload.hpp), frontsteal-paper (papers/workload.hpp) and
// frontsteal-mpi (distributed/mpi_workload.hpp) all tessellate "scene S along path K for F frames"; built
// here once, their frames are the same views and cannot drift apart.
//
// OWNERSHIP while frames run: everything is read-only except buffers[id], which only the run of item `id`
// writes (each item runs exactly once per frame), and the scratch each caller passes per worker.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::tess {

struct PathSceneOptions {
  std::string scene;     // what load_scene accepts: plant:N, teapot, a model file
  std::string data_dir;  // where the embedded scenes live
  CameraPathKind path = CameraPathKind::orbit_then_zoom;
  int frames = 24;
  int width = 1280, height = 720;
  TessellationSettings settings;
};

struct PathScene {
  Model model;
  std::vector<PreparedSurface> prepared;
  std::vector<TriangleBuffers> buffers;  // per surface
  std::vector<Camera> cameras;           // per frame
  std::vector<Frustum> frusta;           // per frame
  TessellationSettings settings;
  DenseRegion dense;  // where dense-zoom ends (computed for every path)

  ItemId surfaces() const noexcept { return static_cast<ItemId>(prepared.size()); }
  int frames() const noexcept { return static_cast<int>(cameras.size()); }

  // Surface `id` of frame `f` into buffers[id], with the caller's (per-worker) scratch.
  SurfaceResult tessellate(int f, ItemId id, TessellationScratch& scratch) {
    return tessellate_surface(prepared[id], cameras[f], frusta[f], settings, scratch, buffers[id]);
  }
  // Per surface the centre of its box, and the estimated cost of its tessellation in frame `f` (at least 1):
  // the hints the cost- and locality-aware schedulers are given.
  std::vector<std::array<double, 3>> centres() const;
  std::vector<double> estimated_costs(int f) const;
};

// Loads the scene, prepares its surfaces and places the cameras. Throws what load_scene throws (ModelError,
// std::invalid_argument) and std::invalid_argument for a scene without surfaces.
PathScene make_path_scene(const PathSceneOptions& options);

}  // namespace frontsteal::tess
