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

}  // namespace frontsteal::tess
