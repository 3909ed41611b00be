// view_camera.cpp — the viewer's orbit-and-walk camera (view_camera.hpp).
#include "render/view_camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace frontsteal::render {

ViewCamera::ViewCamera(const tess::Box& box) : box_(box) { reset(); }

void ViewCamera::reset() {
  radius_ = std::max(1e-9, 0.5 * glm::length(box_.hi - box_.lo));
  target_ = box_.centre();
  yaw_ = 0;
  pitch_ = std::atan2(0.9, 1.6);
  distance_ = radius_ * std::hypot(1.6, 0.9);
}

void ViewCamera::orbit(double dx, double dy) {
  constexpr double kPerPixel = 0.3 * std::numbers::pi / 180;
  constexpr double kMaxPitch = 85.0 * std::numbers::pi / 180;
  yaw_ -= dx * kPerPixel;
  pitch_ = std::clamp(pitch_ + dy * kPerPixel, -kMaxPitch, kMaxPitch);
}

void ViewCamera::zoom(double steps) {
  distance_ = std::clamp(distance_ * std::pow(0.85, steps), 1e-3 * radius_, 50 * radius_);
}

void ViewCamera::walk(double forward, double right, double up) {
  const glm::dvec3 ahead(-std::cos(yaw_), -std::sin(yaw_), 0);  // horizontal, from the eye towards the target
  const glm::dvec3 side(std::sin(yaw_), -std::cos(yaw_), 0);    // ahead × z
  target_ += 0.05 * radius_ * (forward * ahead + right * side + up * glm::dvec3(0, 0, 1));
}

tess::Camera ViewCamera::camera(int width, int height) const {
  tess::Camera cam;
  cam.width = width;
  cam.height = height;
  cam.up = {0, 0, 1};
  cam.near_plane = 1e-3 * radius_;  // as camera_on_path
  cam.far_plane = 20.0 * radius_ + distance_;
  cam.target = target_;
  cam.eye = target_ + distance_ * glm::dvec3(std::cos(pitch_) * std::cos(yaw_), std::cos(pitch_) * std::sin(yaw_),
                                             std::sin(pitch_));
  return cam;
}

std::string ViewCamera::describe(const tess::Camera& c) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "eye=%.17g,%.17g,%.17g target=%.17g,%.17g,%.17g up=%.17g,%.17g,%.17g fovy=%.17g near=%.17g far=%.17g size=%dx%d",
      c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.fovy_radians,
      c.near_plane, c.far_plane, c.width, c.height);
  return line;
}

}  // namespace frontsteal::render
