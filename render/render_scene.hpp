// render_scene.hpp — the scene a greedy renderer draws: ts::load_scene, an empty scene refused, and connected
// components assigned where the scene has none (the per-component swap needs them). frontsteal-render and
// frontsteal-view load their --scene through it, so both draw the same components.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "tessellate/model.hpp"

namespace frontsteal::render {

// Throws std::runtime_error: "cannot load scene 'S': why" or "scene 'S' has no surfaces".
tess::Model load_render_scene(const std::string& spec, const std::string& data_dir);

// For mains: the same, but a failure is printed as "program: why" on stderr and gives no model (exit 2 then).
std::optional<tess::Model> load_render_scene_or_report(std::string_view program, const std::string& spec,
                                                       const std::string& data_dir);

}  // namespace frontsteal::render
