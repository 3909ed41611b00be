// path_scene.cpp — loading a scene and placing it along its camera path (path_scene.hpp).
#include "tessellate/path_scene.hpp"

#include <algorithm>
#include <stdexcept>

#include "tessellate/scene_generator.hpp"

namespace frontsteal::tess {

std::vector<std::array<double, 3>> PathScene::centres() const {
  std::vector<std::array<double, 3>> out;
  out.reserve(prepared.size());
  for (const PreparedSurface& p : prepared) {
    const glm::dvec3 c = p.box.centre();
    out.push_back({c.x, c.y, c.z});
  }
  return out;
}

std::vector<double> PathScene::estimated_costs(int f) const {
  std::vector<double> out;
  out.reserve(prepared.size());
  for (const PreparedSurface& p : prepared) {
    out.push_back(std::max(1.0, estimate_cost(p, plan_surface(p, cameras[f], frusta[f], settings), settings)));
  }
  return out;
}

PathScene make_path_scene(const PathSceneOptions& o) {
  PathScene s;
  s.model = load_scene(o.scene, o.data_dir);
  if (s.model.surfaces.empty()) throw std::invalid_argument("scene '" + o.scene + "' has no surfaces");
  s.prepared.reserve(s.model.surfaces.size());
  for (const Surface& surface : s.model.surfaces) s.prepared.push_back(prepare_surface(surface));
  s.buffers.resize(s.prepared.size());
  s.settings = o.settings;
  const Box box = model_box(s.model);
  s.dense = densest_region(s.model);
  for (int f = 0; f < o.frames; ++f) {
    // orbit-then-zoom is camera_on_path itself: the views every tool used before paths had names
    s.cameras.push_back(camera_on(o.path, box, f, o.frames, o.width, o.height, &s.dense));
    s.frusta.push_back(Frustum::of(s.cameras.back()));
  }
  return s;
}

}  // namespace frontsteal::tess
