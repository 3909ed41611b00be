// render_scene.cpp — loading a scene for greedy rendering (render_scene.hpp).
#include "render/render_scene.hpp"

#include <algorithm>
#include <iostream>
#include <stdexcept>

#include "tessellate/camera_path.hpp"
#include "tessellate/components.hpp"
#include "tessellate/scene_generator.hpp"

namespace frontsteal::render {

tess::Model load_render_scene(const std::string& spec, const std::string& data_dir) {
  tess::Model model;
  try {
    model = tess::load_scene(spec, data_dir);
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot load scene '" + spec + "': " + e.what());
  }
  if (model.surfaces.empty()) throw std::runtime_error("scene '" + spec + "' has no surfaces");
  if (std::any_of(model.surfaces.begin(), model.surfaces.end(),
                  [](const tess::Surface& s) { return s.component < 0; })) {
    const tess::Box box = tess::model_box(model);
    tess::assign_components(model, 1e-6 * std::max(1.0, glm::length(box.hi - box.lo)));
  }
  return model;
}

std::optional<tess::Model> load_render_scene_or_report(std::string_view program, const std::string& spec,
                                                       const std::string& data_dir) {
  try {
    return load_render_scene(spec, data_dir);
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return std::nullopt;
  }
}

}  // namespace frontsteal::render
