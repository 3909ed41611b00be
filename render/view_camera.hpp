// view_camera.hpp — the viewer's camera: an orbit around a target (yaw, pitch, distance) that can also walk
// (target and eye move together). Every input is a discrete step, not a time-scaled motion, so a fixed key
// sequence gives the same camera on any machine at any frame rate (the Xvfb test relies on it).
//
// It starts where the batch paths start (tessellate/camera_path.hpp, frame 0 of the orbit: eye = centre +
// radius·(1.6, 0, 0.9), looking at the centre, z up), with the same near and far planes.
#pragma once

#include <string>

#include "tessellate/camera.hpp"
#include "tessellate/culling.hpp"

namespace frontsteal::render {

class ViewCamera {
 public:
  explicit ViewCamera(const tess::Box& box);

  void orbit(double dx_pixels, double dy_pixels);  // mouse drag: 0.3° per pixel; pitch kept within ±85°
  void zoom(double steps);                         // wheel notches / keys: distance × 0.85^steps
  void walk(double forward_steps, double right_steps, double up_steps);  // 5 % of the model radius per step
  void reset();

  tess::Camera camera(int width, int height) const;
  // One line: eye, target, up, fovy, near, far and size, %.17g, for tests to rebuild the very same camera.
  static std::string describe(const tess::Camera& camera);

 private:
  tess::Box box_;
  double radius_ = 1;
  glm::dvec3 target_{0};
  double yaw_ = 0, pitch_ = 0, distance_ = 1;
};

}  // namespace frontsteal::render
