// camera_path.hpp — deterministic camera paths over a model: an orbit, a zoom into a small part of the
// model (the case that unbalances round-robin allocation, paper §3), a walkthrough among the parts, and a zoom
// that ends on the model's densest region. Frame k of n is a pure function of (model bounds, densest region,
// k, n), so every scheduler and every run sees the same views.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include "tessellate/camera.hpp"
#include "tessellate/culling.hpp"
#include "tessellate/model.hpp"

namespace frontsteal::tess {

inline Box model_box(const Model& m) {
  Box box{glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (const Surface& s : m.surfaces) {
    const Box b = control_box(s.patch);
    box.lo = glm::min(box.lo, b.lo);
    box.hi = glm::max(box.hi, b.hi);
  }
  return box;
}

// Half the frames orbit the whole model from above; the other half fly into the box's corner region
// (the first 8% of its diagonal), ending close enough that only a small part of the model is in view.
inline Camera camera_on_path(const Box& box, int frame, int frames, int width = 1280, int height = 720) {
  const glm::dvec3 centre = box.centre();
  const glm::dvec3 extent = box.hi - box.lo;
  const double radius = 0.5 * glm::length(extent);
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.up = {0, 0, 1};
  cam.near_plane = 1e-3 * radius;
  cam.far_plane = 20.0 * radius;
  const int orbit_frames = frames / 2;
  if (frame < orbit_frames) {
    const double a = 2.0 * std::numbers::pi * frame / std::max(1, orbit_frames);
    cam.eye = centre + radius * glm::dvec3(1.6 * std::cos(a), 1.6 * std::sin(a), 0.9);
    cam.target = centre;
    return cam;
  }
  const double t =
      frames - orbit_frames > 1 ? static_cast<double>(frame - orbit_frames) / (frames - orbit_frames - 1) : 1.0;
  const glm::dvec3 focus = box.lo + 0.08 * extent + glm::dvec3(0, 0, 0.3 * extent.z);
  const glm::dvec3 start = centre + radius * glm::dvec3(1.6, 0.0, 0.9);
  const glm::dvec3 end = focus + 0.03 * radius * glm::dvec3(1.0, -1.0, 0.6);
  const double ease = t * t * (3 - 2 * t);
  cam.eye = start + ease * (end - start);
  cam.target = centre + ease * (focus - centre);
  return cam;
}

// The paths a renderer can follow (paper §5 uses a walkthrough and zooms; Table 1 an orbit).
enum class CameraPathKind { orbit, zoom, walkthrough, orbit_then_zoom, dense_zoom };

inline const char* name(CameraPathKind k) {
  switch (k) {
    case CameraPathKind::orbit: return "orbit";
    case CameraPathKind::zoom: return "zoom";
    case CameraPathKind::walkthrough: return "walkthrough";
    case CameraPathKind::orbit_then_zoom: return "orbit-then-zoom";
    case CameraPathKind::dense_zoom: return "dense-zoom";
  }
  return "?";
}

inline std::optional<CameraPathKind> camera_path_named(std::string_view n) {
  for (auto k : {CameraPathKind::orbit, CameraPathKind::zoom, CameraPathKind::walkthrough,
                 CameraPathKind::orbit_then_zoom, CameraPathKind::dense_zoom}) {
    if (n == name(k)) return k;
  }
  return std::nullopt;
}

// The model's densest region: the cell of a grid over the model's box holding the most patch centres, ties
// broken by the larger summed control-box volume, then by the lowest cell. The cells are cubes of
// `parts` × the median control-box diagonal of the surfaces, so a cell is about one part (a flange, an elbow)
// whatever the model's overall size. Its box is the union of the control boxes of the surfaces centred in it.
// A zoom that ends close to it puts a few surfaces large on screen, so that their view-dependent cost
// dominates the frame (paper §3: the case static allocation cannot balance).
struct DenseRegion {
  Box box;
  int surfaces = 0;
  double cell_edge = 0;
};

inline DenseRegion densest_region(const Model& m, double parts = 1.0) {
  DenseRegion best;
  if (m.surfaces.empty()) return best;
  const Box all = model_box(m);
  const glm::dvec3 extent = all.hi - all.lo;
  std::vector<double> diagonals;
  for (const Surface& s : m.surfaces) {
    const Box b = control_box(s.patch);
    diagonals.push_back(glm::length(b.hi - b.lo));
  }
  std::nth_element(diagonals.begin(), diagonals.begin() + static_cast<std::ptrdiff_t>(diagonals.size() / 2),
                   diagonals.end());
  double edge = parts * diagonals[diagonals.size() / 2];
  if (!(edge > 0)) edge = std::max({extent.x, extent.y, extent.z, 1e-300}) / 96;
  best.cell_edge = edge;
  struct Cell {
    int count = 0;
    double volume = 0;
    Box box{glm::dvec3(1e300), glm::dvec3(-1e300)};
  };
  std::map<std::tuple<long, long, long>, Cell> grid;  // ordered: ties go to the lowest cell, deterministically
  for (const Surface& s : m.surfaces) {
    const Box b = control_box(s.patch);
    const glm::dvec3 c = (b.centre() - all.lo) / edge;
    Cell& cell = grid[{static_cast<long>(std::floor(c.x)), static_cast<long>(std::floor(c.y)),
                       static_cast<long>(std::floor(c.z))}];
    ++cell.count;
    const glm::dvec3 e = b.hi - b.lo;
    cell.volume += e.x * e.y * e.z;
    cell.box.lo = glm::min(cell.box.lo, b.lo);
    cell.box.hi = glm::max(cell.box.hi, b.hi);
  }
  const Cell* top = nullptr;
  for (const auto& [key, cell] : grid) {
    if (!top || cell.count > top->count || (cell.count == top->count && cell.volume > top->volume)) top = &cell;
  }
  best.box = top->box;
  best.surfaces = top->count;
  return best;
}

// Frame k of n of a path; like camera_on_path, a pure function of (box, kind, k, n).
//   orbit: one turn around the whole model from above; zoom: from the overview into the corner region;
//   walkthrough: low among the parts (see eye_z below), along the box's diagonal, looking ahead and slightly
//   down, swaying left and right; orbit_then_zoom: camera_on_path; dense_zoom: needs `dense`
//   (densest_region): from the overview of camera_on_path's zoom to a close view of the dense region, ending at
//   0.6 of its box's diagonal from its centre, looking at it.
inline Camera camera_on(CameraPathKind kind, const Box& box, int frame, int frames, int width, int height,
                        const DenseRegion* dense = nullptr) {
  switch (kind) {
    case CameraPathKind::orbit_then_zoom: return camera_on_path(box, frame, frames, width, height);
    case CameraPathKind::orbit: return camera_on_path(box, frame, 2 * std::max(1, frames), width, height);
    case CameraPathKind::zoom: return camera_on_path(box, frames + frame, 2 * std::max(1, frames), width, height);
    case CameraPathKind::dense_zoom: {
      if (!dense) throw std::invalid_argument("the dense-zoom camera path needs the model's densest region");
      Camera cam = camera_on_path(box, 0, 2, width, height);  // near/far planes and viewport
      const glm::dvec3 centre = box.centre();
      const double radius = 0.5 * glm::length(box.hi - box.lo);
      const glm::dvec3 focus = dense->box.centre();
      const double reach = 0.6 * std::max(glm::length(dense->box.hi - dense->box.lo), 1e-6 * radius);
      const double t = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 1.0;
      const double ease = t * t * (3 - 2 * t);
      const glm::dvec3 start = centre + radius * glm::dvec3(1.6, 0.0, 0.9);
      const glm::dvec3 end = focus + reach * glm::normalize(glm::dvec3(1.0, -1.0, 0.8));
      cam.eye = start + ease * (end - start);
      cam.target = centre + ease * (focus - centre);
      cam.near_plane = std::min(cam.near_plane, 1e-2 * reach);
      return cam;
    }
    case CameraPathKind::walkthrough: break;
  }
  Camera cam = camera_on_path(box, 0, 2, width, height);  // near/far planes and viewport
  const glm::dvec3 extent = box.hi - box.lo;
  const double t = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
  // Eye height: a fifth of the model's height plus 2 % of its diagonal, but never above 0.6 of its height, so
  // that on large plants (diagonal ~ 475 for plant:15906) the walk stays among the parts (tank tops, risers)
  // instead of flying over them; small plants (plant:1201: ~4.4 of ~12) are unchanged.
  const double eye_z = std::min(0.2 * extent.z + 0.02 * glm::length(extent), 0.6 * extent.z);
  const glm::dvec3 a = box.lo + glm::dvec3(0.05 * extent.x, 0.05 * extent.y, eye_z);
  const glm::dvec3 b = box.lo + glm::dvec3(0.95 * extent.x, 0.95 * extent.y, a.z - box.lo.z);
  cam.eye = a + t * (b - a);
  const glm::dvec3 ahead = glm::normalize(b - a);
  const glm::dvec3 side = glm::normalize(glm::cross(ahead, glm::dvec3(0, 0, 1)));
  const double sway = 0.35 * std::sin(2.0 * std::numbers::pi * 1.5 * t);
  cam.target = cam.eye + ahead + sway * side + glm::dvec3(0, 0, -0.25);
  cam.near_plane = 1e-4 * glm::length(extent);
  return cam;
}

}  // namespace frontsteal::tess
