// view_reference — the frontsteal-view test's judge (tests/render/view_xvfb_test.sh): renders the camera the
// viewer printed with its screenshot, headless (EGL, render_synchronized: every surface tessellated for that
// very view), and compares the silhouettes with coverage_iou, the shape check of greedy_renderer_test.
//
// usage: view_reference SCENE SCREENSHOT.png MIN_IOU eye=x,y,z target=x,y,z up=x,y,z fovy=F near=N far=F
//                       size=WxH tolerance=T [rotate=DEG] [out=REFERENCE.png]
// rotate=DEG turns the eye DEG degrees about the target's vertical (the negative control: a different view).
// Prints the IoU; exit 0 when IoU >= MIN_IOU, 1 when below, 2 on bad arguments, 3 without EGL.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <string>

#include "render/greedy_renderer.hpp"
#include "render/headless_gl.hpp"
#include "render/image.hpp"
#include "render/triangle_renderer.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/components.hpp"
#include "tessellate/scene_generator.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

[[noreturn]] void bad(const std::string& what) {
  std::cerr << "view_reference: " << what << '\n';
  std::exit(2);
}

glm::dvec3 vec3(const std::string& key, const std::string& v) {
  glm::dvec3 out;
  if (std::sscanf(v.c_str(), "%lf,%lf,%lf", &out.x, &out.y, &out.z) != 3) bad(key + " expects x,y,z, got '" + v + "'");
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) bad("usage: view_reference SCENE SCREENSHOT.png MIN_IOU key=value ...");
  ts::Model model = ts::load_scene(argv[1], FRONTSTEAL_DATA_DIR);
  const rd::Image shot = rd::read_png(argv[2]);
  const double min_iou = std::stod(argv[3]);
  ts::Camera cam;
  ts::TessellationSettings settings;
  double rotate = 0;
  std::string out;
  for (int i = 4; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    if (eq == std::string::npos) bad("expected key=value, got '" + arg + "'");
    const std::string key = arg.substr(0, eq), v = arg.substr(eq + 1);
    if (key == "eye")
      cam.eye = vec3(key, v);
    else if (key == "target")
      cam.target = vec3(key, v);
    else if (key == "up")
      cam.up = vec3(key, v);
    else if (key == "fovy")
      cam.fovy_radians = std::stod(v);
    else if (key == "near")
      cam.near_plane = std::stod(v);
    else if (key == "far")
      cam.far_plane = std::stod(v);
    else if (key == "size") {
      if (std::sscanf(v.c_str(), "%dx%d", &cam.width, &cam.height) != 2) bad("size expects WxH");
    } else if (key == "tolerance")
      settings.pixel_tolerance = std::stod(v);
    else if (key == "rotate")
      rotate = std::stod(v);
    else if (key == "out")
      out = v;
    else
      bad("unknown key '" + key + "'");
  }
  if (rotate != 0) {
    const double a = rotate * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
    const glm::dvec3 d = cam.eye - cam.target;
    cam.eye = cam.target + glm::dvec3(c * d.x - s * d.y, s * d.x + c * d.y, d.z);
  }
  if (shot.width != cam.width || shot.height != cam.height) {
    std::cout << "view_reference: screenshot is " << shot.width << "x" << shot.height << ", camera " << cam.width << "x"
              << cam.height << ": IoU 0\n";
    return 1;
  }
  rd::Image reference;
  try {
    rd::HeadlessGL gl(cam.width, cam.height);
    gl.make_current();
    reference = rd::render_synchronized(model, cam, settings);
    gl.release();
  } catch (const rd::GraphicsError& e) {
    std::cerr << "view_reference: " << e.what() << '\n';
    return 3;
  }
  if (!out.empty()) rd::write_png(reference, out);
  const double iou = rd::coverage_iou(shot, reference, rd::TriangleRenderer::kBackground);
  const std::size_t covered = rd::covered_pixels(reference, rd::TriangleRenderer::kBackground);
  std::cout << "view_reference: IoU " << iou << " (minimum " << min_iou << "), reference covers " << covered << " of "
            << cam.width * cam.height << " pixels"
            << (rotate != 0 ? ", eye rotated " + std::to_string(rotate) + " deg" : "") << '\n';
  return iou >= min_iou && covered > 0 ? 0 : 1;
}
