// brepmesh_measure.hpp — brepmesh_comparison's measurement: one CAD file meshed by frontsteal's tessellator and by
// Open CASCADE's BRepMesh_IncrementalMesh at each ε, timed, counted, and the deviation from the exact surface
// sampled for both the same way (brepmesh_comparison.cpp's header says how).
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace frontsteal::brepmesh {

struct Options {
  int repeats = 5;
  std::vector<double> eps_fractions{1e-3, 2.5e-4};
  double angle = 3.0;
  int max_steps = 1024;
  std::vector<std::string> files;
  std::string out = "out";
};

struct Timing {
  double median = 0, min = 0, max = 0;  // milliseconds
};

// The deviation from the exact surface over the barycentric lattice of step 1/4 without its 3 vertices.
struct Deviation {
  double max = 0, sum = 0;
  // At the vertices themselves the distance must be ~0 (rounding, and for OCCT the edge tolerance on boundary
  // nodes): a large value means nodes and (u, v) do not match, and the samples would measure nonsense.
  double vertex_max = 0;
  std::uint64_t samples = 0;
  void add(double d) {
    max = std::max(max, d);
    sum += d;
    ++samples;
  }
  double mean() const { return samples ? sum / static_cast<double>(samples) : 0.0; }
};

// One file at one ε.
struct Row {
  std::string file;
  int faces = 0, faces_compared = 0, surfaces = 0, trimmed = 0;
  double diagonal = 0, eps_fraction = 0, eps = 0, import_ms = 0;
  // ours
  Timing ours;
  std::uint64_t our_triangles = 0;
  int capped = 0;
  std::uint64_t inconsistencies = 0;
  std::uint64_t partial_cells = 0, constrained_pieces = 0;  // pieces too large for ear clipping (see the tessellator)
  Deviation our_dev;
  // BRepMesh
  Timing occt_serial, occt_parallel, occt_serial_imported;
  bool timed_imported_only = false;
  std::uint64_t occt_triangles_all = 0, occt_triangles = 0, occt_triangles_parallel = 0;
  std::uint64_t occt_triangles_default_angle = 0;  // compared faces, BRepMesh's default angular deflection 0.5
  int occt_status = 0;
  Deviation occt_dev;
  // The largest tolerance of an edge of the compared faces: BRepMesh puts boundary nodes on the 3D edge curves,
  // which may lie this far from the surface, so its deviation cannot be expected below it.
  double edge_tolerance = 0;
};

// Every ε of `o` on one file (a .gz is unpacked into `scratch_dir` first). Throws std::runtime_error when the
// file cannot be read.
std::vector<Row> compare_file(const Options& o, const std::string& original, const std::filesystem::path& scratch_dir);

}  // namespace frontsteal::brepmesh
