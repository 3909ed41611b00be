// scene_generator.hpp — procedural CAD-like scenes: a process-plant rig of tanks, pipes, elbows, flanges and
// bolted plates, built from exact rational Bézier patches and trimmed by bolt holes. Deterministic by seed;
// exactly the requested number of surfaces (the paper's models had 1,201 / 3,392 / 4,101 / 5,302 / 10,604 /
// 15,906; any count ≥ 1 works).
//
// Shapes (all exact, no approximation of circles):
//   - surfaces of revolution: a rational profile (ρ(t), z(t)) swept by four rational quadratic quarter circles
//     (weights 1, √2/2, 1); the patch has control points (ρ_i c_j, ρ_i s_j, z_i) and weights w_i w_j;
//   - tanks (cylinder + two hemispherical heads, closed solids, 12 patches), pipes (cylinders, 4 patches per
//     run), elbows (a quarter torus, 4 biquadratic patches), flanges (flat rings, 4 patches, each trimmed by
//     two bolt holes), base plates (a bilinear patch trimmed by bolt holes, some with a chamfered outer loop);
//   - a bay = base plate + tank + a pipe run (pipe, elbow, riser, flange); bays are laid on a square grid and
//     the remainder of the count is filled with bolted floor plates.
// Normals: solids' S_u × S_v points outwards (checked at build time and flipped where needed). Components are
// assigned from adjacency (components.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "tessellate/model.hpp"

namespace frontsteal::tess {

struct SceneOptions {
  int surfaces = 5302;
  std::uint64_t seed = 1;
};

Model generate_plant(const SceneOptions& options);

// "teapot", "teacup", "teaspoon" (the data files), "plant:<N>[:seed]" (generate_plant), or a path to a model
// file. Throws ModelError / std::invalid_argument with a clear message.
Model load_scene(const std::string& spec, const std::string& data_dir);

}  // namespace frontsteal::tess
