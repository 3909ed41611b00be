// mesh_export.hpp — a tessellated frame written out for other tools: Wavefront OBJ (text, one group per
// surface, with normals and (u, v) as texture coordinates) or PLY (binary little-endian, one mesh, the surface
// index as a per-face property so viewers can colour by surface).
#pragma once

#include <iosfwd>
#include <span>
#include <string>

#include "tessellate/grid_tessellator.hpp"

namespace frontsteal::tess {

struct MeshPart {
  std::string name;
  const TriangleBuffers* buffers = nullptr;
};

void write_obj(std::ostream& out, std::span<const MeshPart> parts);
void write_ply(std::ostream& out, std::span<const MeshPart> parts);
// By the file's extension (.obj or .ply); throws std::runtime_error naming the path when it cannot write.
void write_mesh_file(const std::string& path, std::span<const MeshPart> parts);

}  // namespace frontsteal::tess
