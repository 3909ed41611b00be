// camera.hpp — a perspective camera (view, projection, viewport) and its view frustum.
//
// The camera is the per-frame input of tessellation (paper §2: step sizes depend on the view). Frustum planes
// come from the combined matrix M = P·V (Gribb & Hartmann, 2001): plane_k = row_4 ± row_i, normalized, inside
// where plane · (x, y, z, 1) ≥ 0.
#pragma once

#include <array>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace frontsteal::tess {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 5.0};
  glm::dvec3 target{0.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
  double fovy_radians = 0.8;  // vertical field of view
  int width = 1280;           // viewport, pixels
  int height = 720;
  double near_plane = 0.05;
  double far_plane = 1000.0;

  double aspect() const noexcept { return static_cast<double>(width) / height; }
  glm::dmat4 view() const { return glm::lookAt(eye, target, up); }
  glm::dmat4 projection() const { return glm::perspective(fovy_radians, aspect(), near_plane, far_plane); }
  glm::dmat4 view_projection() const { return projection() * view(); }
  // Unit vector along the line of sight.
  glm::dvec3 forward() const { return glm::normalize(target - eye); }
  // Pixels per unit of (x/z) at the image centre: f_px = (H/2) / tan(fovy/2).
  double focal_pixels() const { return 0.5 * height / std::tan(0.5 * fovy_radians); }
  // Largest |x/z| and |y/z| inside the frustum: tan of the half field of view in x and in y.
  double tan_half_fovx() const { return std::tan(0.5 * fovy_radians) * aspect(); }
  double tan_half_fovy() const { return std::tan(0.5 * fovy_radians); }

  // Window coordinates (pixels, origin bottom-left) and depth along the line of sight of a point.
  glm::dvec3 project(const glm::dvec3& p) const {
    const glm::dvec4 clip = view_projection() * glm::dvec4(p, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return {(ndc.x + 1.0) * 0.5 * width, (ndc.y + 1.0) * 0.5 * height, clip.w};
  }
};

struct Frustum {
  std::array<glm::dvec4, 6> planes;  // left, right, bottom, top, near, far; inside: dot(plane, (p,1)) >= 0

  static Frustum of(const Camera& camera) {
    const glm::dmat4 m = glm::transpose(camera.view_projection());  // rows of P·V as columns
    Frustum f;
    f.planes = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2], m[3] - m[2]};
    for (glm::dvec4& p : f.planes) p /= glm::length(glm::dvec3(p));
    return f;
  }
  bool contains(const glm::dvec3& p) const {
    for (const glm::dvec4& plane : planes) {
      if (glm::dot(plane, glm::dvec4(p, 1.0)) < 0) return false;
    }
    return true;
  }
};

}  // namespace frontsteal::tess
