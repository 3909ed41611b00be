// camera_path.hpp — deterministic camera paths over a model: an orbit, and a zoom into a small part of the
// model (the case that unbalances round-robin allocation, paper §3). Frame k of n is a pure function of
// (model bounds, k, n), so every scheduler and every run sees the same views.
#pragma once

#include <cmath>
#include <numbers>
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
  const double t = frames - orbit_frames > 1 ? static_cast<double>(frame - orbit_frames) / (frames - orbit_frames - 1) : 1.0;
  const glm::dvec3 focus = box.lo + 0.08 * extent + glm::dvec3(0, 0, 0.3 * extent.z);
  const glm::dvec3 start = centre + radius * glm::dvec3(1.6, 0.0, 0.9);
  const glm::dvec3 end = focus + 0.03 * radius * glm::dvec3(1.0, -1.0, 0.6);
  const double ease = t * t * (3 - 2 * t);
  cam.eye = start + ease * (end - start);
  cam.target = centre + ease * (focus - centre);
  return cam;
}

// The paths a renderer can follow (paper §5 uses a walkthrough and zooms; Table 1 an orbit).
enum class CameraPathKind { orbit, zoom, walkthrough, orbit_then_zoom };

inline const char* name(CameraPathKind k) {
  switch (k) {
    case CameraPathKind::orbit: return "orbit";
    case CameraPathKind::zoom: return "zoom";
    case CameraPathKind::walkthrough: return "walkthrough";
    case CameraPathKind::orbit_then_zoom: return "orbit-then-zoom";
  }
  return "?";
}

// Frame k of n of a path; like camera_on_path, a pure function of (box, kind, k, n).
//   orbit: one turn around the whole model from above; zoom: from the overview into the corner region;
//   walkthrough: at a fifth of the model's height, along the box's diagonal, looking ahead and slightly
//   down, swaying left and right; orbit_then_zoom: camera_on_path.
inline Camera camera_on(CameraPathKind kind, const Box& box, int frame, int frames, int width, int height) {
  switch (kind) {
    case CameraPathKind::orbit_then_zoom: return camera_on_path(box, frame, frames, width, height);
    case CameraPathKind::orbit: return camera_on_path(box, frame, 2 * std::max(1, frames), width, height);
    case CameraPathKind::zoom: return camera_on_path(box, frames + frame, 2 * std::max(1, frames), width, height);
    case CameraPathKind::walkthrough: break;
  }
  Camera cam = camera_on_path(box, 0, 2, width, height);  // near/far planes and viewport
  const glm::dvec3 extent = box.hi - box.lo;
  const double t = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
  const glm::dvec3 a = box.lo + glm::dvec3(0.05 * extent.x, 0.05 * extent.y, 0.2 * extent.z + 0.02 * glm::length(extent));
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
