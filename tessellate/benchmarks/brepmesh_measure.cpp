// brepmesh_measure.cpp — one CAD file through both meshers (brepmesh_measure.hpp).
#include "tessellate/benchmarks/brepmesh_measure.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <BRepBndLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom_Surface.hxx>
#include <IGESControl_Reader.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include "measure/machine_info.hpp"
#include "tessellate/occt_import.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::brepmesh {

namespace {

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kProgram = "brepmesh_comparison";

// ---- statistics of repeated timings ------------------------------------------------------------------------

Timing summarize(const std::vector<double>& ms) {
  return {frontsteal::median(ms), *std::min_element(ms.begin(), ms.end()), *std::max_element(ms.begin(), ms.end())};
}

template <class F>
Timing time_runs(int repeats, F&& run) {
  std::vector<double> ms;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    run();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return summarize(ms);
}

// ---- deviation: the barycentric lattice of step 1/4 without its 3 vertices ---------------------------------

// Calls f(a, b, c) with a + b + c = 1 at every lattice point i/4 + j/4 + k/4 except the triangle's corners.
template <class F>
void for_each_sample(F&& f) {
  constexpr int kLevel = 4;
  for (int i = 0; i <= kLevel; ++i) {
    for (int j = 0; i + j <= kLevel; ++j) {
      const int k = kLevel - i - j;
      if (i == kLevel || j == kLevel || k == kLevel) continue;
      f(static_cast<double>(i) / kLevel, static_cast<double>(j) / kLevel, static_cast<double>(k) / kLevel);
    }
  }
}

void measure_ours(const ts::BezierPatch& patch, const ts::TriangleBuffers& b, Deviation& dev) {
  for (std::size_t t = 0; t < b.indices.size(); t += 3) {
    const std::uint32_t i0 = b.indices[t], i1 = b.indices[t + 1], i2 = b.indices[t + 2];
    const glm::dvec3 p0(b.positions[i0]), p1(b.positions[i1]), p2(b.positions[i2]);
    const glm::dvec2 q0(b.uvs[i0]), q1(b.uvs[i1]), q2(b.uvs[i2]);
    dev.vertex_max = std::max(dev.vertex_max, glm::length(ts::evaluate(patch, q0.x, q0.y).position - p0));
    for_each_sample([&](double a, double c, double e) {
      const glm::dvec2 uv = a * q0 + c * q1 + e * q2;
      const glm::dvec3 p = a * p0 + c * p1 + e * p2;
      dev.add(glm::length(ts::evaluate(patch, uv.x, uv.y).position - p));
    });
  }
}

// Nodes live in the triangulation's frame and the surface in its own: both are moved to the shape's frame.
void measure_occt(const TopoDS_Face& face, Deviation& dev) {
  TopLoc_Location tri_loc, surf_loc;
  const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, tri_loc);
  const Handle(Geom_Surface) surf = BRep_Tool::Surface(face, surf_loc);
  if (tri.IsNull() || surf.IsNull() || !tri->HasUVNodes()) return;
  const gp_Trsf node_to_shape = tri_loc.Transformation(), surf_to_shape = surf_loc.Transformation();
  for (int t = 1; t <= tri->NbTriangles(); ++t) {
    int n[3];
    tri->Triangle(t).Get(n[0], n[1], n[2]);
    gp_XYZ p[3];
    gp_XY q[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = tri->Node(n[k]).Transformed(node_to_shape).XYZ();
      q[k] = tri->UVNode(n[k]).XY();
    }
    const gp_Pnt corner = surf->Value(q[0].X(), q[0].Y()).Transformed(surf_to_shape);
    dev.vertex_max = std::max(dev.vertex_max, corner.Distance(gp_Pnt(p[0])));
    for_each_sample([&](double a, double c, double e) {
      const gp_XY uv = a * q[0] + c * q[1] + e * q[2];
      const gp_Pnt exact = surf->Value(uv.X(), uv.Y()).Transformed(surf_to_shape);
      dev.add(exact.Distance(gp_Pnt(a * p[0] + c * p[1] + e * p[2])));
    });
  }
}

// ---- reading the file as Open CASCADE sees it (the same readers as occt_import.cpp, errors made fatal) ------

TopoDS_Shape read_shape(const std::string& path) {
  std::string ext = fsys::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") {
    STEPControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw std::runtime_error(path + ": STEP read failed");
    reader.TransferRoots();
    return reader.OneShape();
  }
  if (ext == ".iges" || ext == ".igs") {
    IGESControl_Reader reader;
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw std::runtime_error(path + ": IGES read failed");
    reader.TransferRoots();
    return reader.OneShape();
  }
  BRep_Builder builder;
  TopoDS_Shape shape;
  if (!BRepTools::Read(shape, path.c_str(), builder) || shape.IsNull())
    throw std::runtime_error(path + ": BREP read failed");
  return shape;
}

// The face number in a Surface's name "<stem>_f<face>_p<patch>[_<piece>]" (occt_import.hpp), or -1.
int face_of(const std::string& name) {
  const auto f = name.rfind("_f");
  if (f == std::string::npos) return -1;
  std::size_t end = f + 2;
  while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
  if (end == f + 2 || name.compare(end, 2, "_p") != 0) return -1;
  return std::stoi(name.substr(f + 2, end - f - 2));
}

std::uint64_t occt_triangles(const TopTools_IndexedMapOfShape& faces, const std::set<int>* only) {
  std::uint64_t n = 0;
  for (int k = 1; k <= faces.Extent(); ++k) {
    if (only && !only->count(k - 1)) continue;
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(TopoDS::Face(faces(k)), loc);
    if (!tri.IsNull()) n += static_cast<std::uint64_t>(tri->NbTriangles());
  }
  return n;
}

}  // namespace

std::vector<Row> compare_file(const Options& o, const std::string& original, const fsys::path& scratch_dir) {
  std::string path = original;
  // The gmsh tutorial's STEP file ships gzipped; OCCT reads plain files only.
  if (fsys::path(original).extension() == ".gz") {
    path = (scratch_dir / fsys::path(original).stem()).string();
    const std::string cmd = "gzip -dc '" + original + "' > '" + path + "'";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error(original + ": gzip -dc failed");
  }
  // Ours: import (once, timed apart: a one-time conversion, like loading a model) and prepare.
  ts::Model model;
  const auto t0 = Clock::now();
  const ts::ImportReport report = ts::import_cad_file(path, model);
  const double import_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  std::vector<ts::PreparedSurface> prepared;
  std::set<int> imported_faces;
  for (const ts::Surface& s : model.surfaces) {
    prepared.push_back(ts::prepare_surface(s));
    imported_faces.insert(face_of(s.name));
  }
  // BRepMesh's input: the same file through OCCT's reader; faces in TopExp::MapShapes order, as the importer.
  const TopoDS_Shape shape = read_shape(path);
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  if (faces.Extent() != report.faces) throw std::runtime_error(path + ": face count differs from the importer's");
  TopoDS_Compound imported_only;
  BRep_Builder builder;
  builder.MakeCompound(imported_only);
  for (int k = 1; k <= faces.Extent(); ++k) {
    if (imported_faces.count(k - 1)) builder.Add(imported_only, faces(k));
  }
  double edge_tolerance = 0;
  for (const int f : imported_faces) {
    for (TopExp_Explorer e(faces(f + 1), TopAbs_EDGE); e.More(); e.Next()) {
      edge_tolerance = std::max(edge_tolerance, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
    }
  }
  BRepTools::Clean(shape);
  Bnd_Box box;
  BRepBndLib::AddOptimal(shape, box, /*useTriangulation=*/false, /*useShapeTolerance=*/false);
  const double diagonal = std::sqrt(box.SquareExtent());

  std::vector<Row> rows;
  ts::TessellationSettings settings;
  settings.max_steps = o.max_steps;
  ts::TessellationScratch scratch;
  std::vector<ts::TriangleBuffers> buffers(prepared.size());
  for (const double fraction : o.eps_fractions) {
    Row row;
    row.file = fsys::path(original).filename().string();
    row.faces = report.faces;
    row.faces_compared = static_cast<int>(imported_faces.size());
    row.surfaces = static_cast<int>(prepared.size());
    row.diagonal = diagonal;
    row.eps_fraction = fraction;
    row.eps = fraction * diagonal;
    row.import_ms = import_ms;
    row.edge_tolerance = edge_tolerance;
    const double eps = row.eps;

    // Ours: plan at ε directly (no camera), then triangulate every surface.
    std::vector<ts::SurfaceResult> results(prepared.size());
    row.ours = time_runs(o.repeats, [&] {
      for (std::size_t k = 0; k < prepared.size(); ++k) {
        const ts::PreparedSurface& s = prepared[k];
        ts::SurfacePlan plan;
        plan.epsilon = eps;
        plan.edge_length = std::numeric_limits<double>::infinity();  // size bound off
        const ts::StepSizes d = ts::deviation_steps(s.bounds, eps, o.max_steps + 1);
        plan.capped = d.n_u > o.max_steps || d.n_v > o.max_steps;
        plan.steps = {std::min(d.n_u, o.max_steps), std::min(d.n_v, o.max_steps)};
        results[k] = ts::tessellate_planned(s, plan, settings, scratch, buffers[k]);  // double precision
      }
    });
    for (std::size_t k = 0; k < prepared.size(); ++k) {
      row.our_triangles += results[k].triangles;
      row.capped += results[k].capped;
      row.inconsistencies += results[k].inconsistencies();
      row.partial_cells += results[k].partial_cells;
      row.constrained_pieces += results[k].constrained_pieces;
      row.trimmed += prepared[k].trimmed();
      measure_ours(prepared[k].surface->patch, buffers[k], row.our_dev);
    }

    // BRepMesh, whole shape, one thread then parallel; each run from a clean shape.
    int status = 0;
    const auto time_mesh = [&](const TopoDS_Shape& target, bool parallel) {
      std::vector<double> ms;
      for (int r = 0; r < o.repeats; ++r) {
        BRepTools::Clean(target);  // else BRepMesh keeps a triangulation that already meets ε and does nothing
        const auto t = Clock::now();
        BRepMesh_IncrementalMesh mesher(target, eps, /*isRelative=*/false, o.angle, parallel);
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count());
        status |= mesher.GetStatusFlags();
      }
      return summarize(ms);
    };
    // What the angular deflection does: the compared faces' triangles at BRepMesh's default 0.5 rad (untimed).
    BRepTools::Clean(shape);
    BRepMesh_IncrementalMesh(shape, eps, /*isRelative=*/false, 0.5, false);
    row.occt_triangles_default_angle = occt_triangles(faces, &imported_faces);
    row.occt_parallel = time_mesh(shape, true);
    row.occt_triangles_parallel = occt_triangles(faces, &imported_faces);
    if (imported_faces.size() < static_cast<std::size_t>(faces.Extent())) {
      row.timed_imported_only = true;
      row.occt_serial_imported = time_mesh(imported_only, false);
    }
    // Last: the one-thread whole-shape mesh, which the triangle counts and the deviation are measured on.
    row.occt_serial = time_mesh(shape, false);
    row.occt_status = status;
    row.occt_triangles_all = occt_triangles(faces, nullptr);
    row.occt_triangles = occt_triangles(faces, &imported_faces);
    for (const int f : imported_faces) measure_occt(TopoDS::Face(faces(f + 1)), row.occt_dev);
    std::cerr << kProgram << ": " << row.file << " ε = " << row.eps << ": ours " << row.ours.median << " ms, "
              << row.our_triangles << " triangles; BRepMesh " << row.occt_serial.median << " ms, " << row.occt_triangles
              << " triangles\n";
    rows.push_back(row);
  }
  if (path != original) fsys::remove(path);
  return rows;
}

}  // namespace frontsteal::brepmesh
