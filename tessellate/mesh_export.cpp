// mesh_export.cpp — OBJ and PLY writers (see mesh_export.hpp).
#include "tessellate/mesh_export.hpp"

#include <bit>
#include <cstdint>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace frontsteal::tess {

void write_obj(std::ostream& out, std::span<const MeshPart> parts) {
  // 9 significant digits write every float exactly (max_digits10): the export adds no error of its own.
  const auto precision = out.precision(9);
  out << "# frontsteal tessellated frame: " << parts.size() << " surfaces\n";
  std::size_t base = 1;  // OBJ indices start at 1 and run across the file
  for (const MeshPart& part : parts) {
    const TriangleBuffers& b = *part.buffers;
    if (b.indices.empty()) continue;
    out << "g " << (part.name.empty() ? "surface" : part.name) << "\n";
    for (const glm::vec3& p : b.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const glm::vec2& t : b.uvs) out << "vt " << t.x << " " << t.y << "\n";
    for (const glm::vec3& n : b.normals) out << "vn " << n.x << " " << n.y << " " << n.z << "\n";
    for (std::size_t k = 0; k < b.indices.size(); k += 3) {
      out << "f";
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = base + b.indices[k + c];
        out << " " << i << "/" << i << "/" << i;
      }
      out << "\n";
    }
    base += b.positions.size();
  }
  out.precision(precision);
}

namespace {
template <class T>
void put(std::ostream& out, T value) {
  static_assert(std::endian::native == std::endian::little, "PLY writer assumes a little-endian host");
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}
}  // namespace

void write_ply(std::ostream& out, std::span<const MeshPart> parts) {
  std::size_t vertices = 0, faces = 0;
  for (const MeshPart& part : parts) {
    vertices += part.buffers->positions.size();
    faces += part.buffers->triangle_count();
  }
  out << "ply\nformat binary_little_endian 1.0\ncomment frontsteal tessellated frame\n"
      << "element vertex " << vertices << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n"
      << "element face " << faces << "\nproperty list uchar uint vertex_indices\nproperty uint surface\nend_header\n";
  for (const MeshPart& part : parts) {
    const TriangleBuffers& b = *part.buffers;
    for (std::size_t k = 0; k < b.positions.size(); ++k) {
      for (float f : {b.positions[k].x, b.positions[k].y, b.positions[k].z, b.normals[k].x, b.normals[k].y,
                      b.normals[k].z, b.uvs[k].x, b.uvs[k].y}) {
        put(out, f);
      }
    }
  }
  std::uint32_t base = 0, surface = 0;
  for (const MeshPart& part : parts) {
    const TriangleBuffers& b = *part.buffers;
    for (std::size_t k = 0; k < b.indices.size(); k += 3) {
      put<std::uint8_t>(out, 3);
      for (int c = 0; c < 3; ++c) put<std::uint32_t>(out, base + b.indices[k + c]);
      put<std::uint32_t>(out, surface);
    }
    base += static_cast<std::uint32_t>(b.positions.size());
    ++surface;
  }
}

void write_mesh_file(const std::string& path, std::span<const MeshPart> parts) {
  const bool ply = path.size() >= 4 && path.substr(path.size() - 4) == ".ply";
  const bool obj = path.size() >= 4 && path.substr(path.size() - 4) == ".obj";
  if (!ply && !obj) throw std::runtime_error(path + ": mesh files end in .obj or .ply");
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  if (ply) {
    write_ply(out, parts);
  } else {
    write_obj(out, parts);
  }
  out.flush();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace frontsteal::tess
