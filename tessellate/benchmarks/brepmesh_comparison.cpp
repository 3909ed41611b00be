// brepmesh_comparison — frontsteal's tessellator against Open CASCADE's own mesher, BRepMesh_IncrementalMesh,
// on real CAD files at the same object-space chordal deviation ε (issue 15 §2, "a second peer").
//
// Per file and ε:
//   ours      tess::import_cad_file (in-process; timed once, reported apart), prepare_surface per Surface, then
//             per frame-like run: a SurfacePlan with epsilon = ε, the size bound off (edge_length = +∞: BRepMesh
//             has no edge-length bound either), steps = deviation_steps(bounds, ε, max_steps), and
//             tessellate_trimmed / tessellate_untrimmed into per-surface buffers reused across runs. One thread.
//   BRepMesh  the shape read from the file with OCCT's reader, its triangulations removed (BRepTools::Clean)
//             before every run so that each run meshes from scratch, then
//             BRepMesh_IncrementalMesh(shape, ε, relative = false, angle, parallel), parallel off and on.
//             The angular deflection is a command-line value, by default 3.0 rad: practically off, so that the
//             linear deflection ε alone decides, as it does for us (on halter.igs the triangle count still fell
//             13% from 1.5 to 3.0 rad at the coarser ε; the report also gives the counts at OCCT's default 0.5).
// Deviation, the same way for both: every triangle is sampled at the 12 non-vertex points of the barycentric
// lattice of step 1/4 (edge midpoints, quarter points and 3 interior points); at each, the triangle's 3D
// point and its (u, v) are interpolated from its vertices (ours: TriangleBuffers::positions/uvs; OCCT:
// Poly_Triangulation's nodes and UV nodes), the exact surface is evaluated at that (u, v) (ours: tess::evaluate
// on the Bézier patch, an exact conversion of the face's surface; OCCT: the face's Geom_Surface, D0), and the
// distance between the two is taken. Max over all samples and mean over all samples (every triangle weighs
// the same). This measures how far the triangles are from the surface at their own parameters, i.e. the
// interior (chordal) error; it does not measure how well the trimmed boundary follows the true edge curves
// (ours: the importer's p-curve polylines; BRepMesh: its edge discretization).
// Only faces that frontsteal imported are compared (a face whose B-spline degree exceeds 7 is skipped by the
// importer); BRepMesh still meshes and is timed on the whole shape, as the issue asks, and is also timed on a
// compound of the imported faces alone where some were skipped.
//
// Every figure printed is measured on the machine named in the report. Times: median, min and max of
// --repeats runs. Writes brepmesh.{md,csv,json} to --out.
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

#include "core/cli_args.hpp"
#include "core/machine_info.hpp"
#include "tessellate/occt_import.hpp"
#include "tessellate/surface_tessellator.hpp"

#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif

namespace {

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr std::string_view kProgram = "brepmesh_comparison";
constexpr std::string_view kUsage = R"(usage: brepmesh_comparison [options]

Meshes the real CAD files (occt-misc, calculix-cgx-examples, gmsh-doc) with frontsteal's tessellator and with
Open CASCADE's BRepMesh_IncrementalMesh at the same object-space deviation, and compares time, triangles and
the measured deviation. Prints the table and writes brepmesh.{md,csv,json} to --out.

options:
  --repeats R     timed runs per configuration (median, min, max)                     (default 5)
  --eps LIST      ε as fractions of the bounding-box diagonal, comma-separated      (default 1e-3,2.5e-4)
  --angle RAD     BRepMesh's angular deflection (3.0: practically off)                (default 3.0)
  --max-steps N   our step cap per direction and patch                               (default 1024)
  --file PATH     compare this file only (repeatable; default: the five files below)
  --out DIR       results directory                                                   (default out)
  --help          this text
)";

struct Options {
  int repeats = 5;
  std::vector<double> eps_fractions{1e-3, 2.5e-4};
  double angle = 3.0;
  int max_steps = 1024;
  std::vector<std::string> files;
  std::string out = "out";
};

Options parse(int argc, char** argv) {
  namespace cli = frontsteal::cli;
  Options o;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--repeats") {
      o.repeats = cli::parse_number<int>(kProgram, a, args.value(), 1, 1000);
    } else if (a == "--eps") {
      o.eps_fractions.clear();
      std::stringstream list{std::string(args.value())};
      for (std::string item; std::getline(list, item, ',');) {
        o.eps_fractions.push_back(cli::parse_number<double>(kProgram, a, item, 1e-7, 0.5));
      }
      if (o.eps_fractions.empty()) cli::usage_error(kProgram, "--eps expects a comma-separated list");
    } else if (a == "--angle") {
      o.angle = cli::parse_number<double>(kProgram, a, args.value(), 0.01, 3.2);
    } else if (a == "--max-steps") {
      o.max_steps = cli::parse_number<int>(kProgram, a, args.value(), 1, 8192);
    } else if (a == "--file") {
      o.files.emplace_back(args.value());
    } else if (a == "--out") {
      o.out = args.value();
    } else {
      cli::usage_error(kProgram, "unknown option '" + std::string(a) + "'");
    }
  }
  if (o.files.empty()) {
    o.files = {"/usr/share/opencascade/data/iges/bearing.iges", "/usr/share/opencascade/data/occ/Top.brep",
               "/usr/share/opencascade/data/occ/hammer.brep",
               "/usr/share/doc/calculix-cgx-examples/examples/cad/halter.igs",
               "/usr/share/doc/gmsh-doc/doc/gmsh/tutorial/t20_data.step.gz"};
  }
  return o;
}

// ---- statistics of repeated timings ------------------------------------------------------------------------

struct Timing {
  double median = 0, min = 0, max = 0;  // milliseconds
};

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
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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
  if (!BRepTools::Read(shape, path.c_str(), builder) || shape.IsNull()) throw std::runtime_error(path + ": BREP read failed");
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

// ---- one file ------------------------------------------------------------------------------------------------

struct Row {
  std::string file;
  int faces = 0, faces_compared = 0, surfaces = 0, trimmed = 0;
  double diagonal = 0, eps_fraction = 0, eps = 0, import_ms = 0;
  // ours
  Timing ours;
  std::uint64_t our_triangles = 0;
  int capped = 0;
  std::uint64_t inconsistencies = 0;
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
        if (s.trimmed()) {
          results[k] = ts::tessellate_trimmed(s, plan, settings, scratch, buffers[k]);
        } else {
          ts::tessellate_untrimmed(s.surface->patch, plan.steps, buffers[k], scratch.v_basis);
          results[k] = {};
          results[k].capped = plan.capped;
          results[k].triangles = static_cast<std::uint32_t>(buffers[k].triangle_count());
        }
      }
    });
    for (std::size_t k = 0; k < prepared.size(); ++k) {
      row.our_triangles += results[k].triangles;
      row.capped += results[k].capped;
      row.inconsistencies += results[k].inconsistencies();
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

// ---- report ----------------------------------------------------------------------------------------------------

std::string fmt(double x, int digits = 3) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string timing(const Timing& t) { return fmt(t.median) + " [" + fmt(t.min) + ", " + fmt(t.max) + "]"; }

std::string timing_json(const Timing& t) {
  return "{\"median\": " + fmt(t.median, 6) + ", \"min\": " + fmt(t.min, 6) + ", \"max\": " + fmt(t.max, 6) + "}";
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  std::error_code ec;
  fsys::create_directories(o.out, ec);
  if (ec) {
    std::cerr << kProgram << ": cannot create " << o.out << ": " << ec.message() << '\n';
    return 1;
  }
  const fsys::path scratch_dir = fsys::temp_directory_path() / ("frontsteal_brepmesh_" + std::to_string(::getpid()));
  fsys::create_directories(scratch_dir);
  const std::string load_before = frontsteal::load_average_1min();
  std::vector<Row> rows;
  std::vector<std::string> missing;
  for (const std::string& file : o.files) {
    if (!fsys::exists(file)) {
      missing.push_back(file);
      std::cerr << kProgram << ": " << file << " is missing (bootstrap.sh installs occt-misc, calculix-cgx-examples, "
                << "gmsh-doc); skipped\n";
      continue;
    }
    try {
      for (Row& r : compare_file(o, file, scratch_dir)) rows.push_back(std::move(r));
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": " << e.what() << '\n';
      fsys::remove_all(scratch_dir, ec);
      return 1;
    }
  }
  fsys::remove_all(scratch_dir, ec);
  const std::string load_after = frontsteal::load_average_1min();

  // Stamp: machine, commit, date, load average.
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  const bool busy = std::atof(load_before.c_str()) > 1.0 || std::atof(load_after.c_str()) > 1.0;
  std::ostringstream stamp;
  stamp << "Measured " << date << " on " << frontsteal::cpu_model() << " (" << std::thread::hardware_concurrency()
        << " hardware threads), commit " << FRONTSTEAL_GIT_COMMIT << ", 1-minute load average " << load_before
        << " before and " << load_after << " after"
        << (busy ? " — the machine was busy (load > 1): times are inflated and noisy, ratios less so" : "")
        << ". Times are median [min, max] of " << o.repeats << " runs, in ms. BRepMesh: linear deflection ε absolute, "
        << "angular deflection " << o.angle << " rad, other parameters at their defaults; ours: steps from the "
        << "deviation bound at ε, size bound off, step cap " << o.max_steps << ", one thread.";

  std::ostringstream table;
  table << "| file | faces (compared) | ε / diagonal | ε | ours ms | BRepMesh 1T ms | BRepMesh par ms | "
           "BRepMesh 1T, compared faces only, ms | ours tri | BRepMesh tri (compared / all) | BRepMesh tri at 0.5 rad | ours max dev | ours mean dev | "
           "BRepMesh max dev | BRepMesh mean dev | time 1T ÷ ours | time par ÷ ours | tri BRepMesh ÷ ours |\n"
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    table << "| " << r.file << " | " << r.faces << " (" << r.faces_compared << ") | " << fmt(r.eps_fraction) << " | "
          << fmt(r.eps) << " | " << timing(r.ours) << " | " << timing(r.occt_serial) << " | " << timing(r.occt_parallel)
          << " | " << (r.timed_imported_only ? timing(r.occt_serial_imported) : std::string("= whole shape")) << " | "
          << r.our_triangles << " | " << r.occt_triangles << " / " << r.occt_triangles_all << " | "
          << r.occt_triangles_default_angle << " | " << fmt(r.our_dev.max)
          << " | " << fmt(r.our_dev.mean()) << " | " << fmt(r.occt_dev.max) << " | " << fmt(r.occt_dev.mean()) << " | "
          << fmt(r.occt_serial.median / r.ours.median) << " | " << fmt(r.occt_parallel.median / r.ours.median) << " | "
          << fmt(static_cast<double>(r.occt_triangles) / static_cast<double>(r.our_triangles)) << " |\n";
  }
  std::ostringstream notes;
  for (const Row& r : rows) {
    {
      notes << "- " << r.file << " at ε/diag " << fmt(r.eps_fraction) << ": largest edge tolerance " << fmt(r.edge_tolerance)
            << " (" << fmt(r.edge_tolerance / r.eps) << " ε); " << r.capped << " surfaces held at the step cap, "
            << r.inconsistencies << " audit inconsistencies, BRepMesh status flags " << r.occt_status
            << ", BRepMesh parallel triangles " << r.occt_triangles_parallel << " (1T: " << r.occt_triangles
            << "), largest distance at a vertex: ours " << fmt(r.our_dev.vertex_max) << ", BRepMesh "
            << fmt(r.occt_dev.vertex_max) << "\n";
    }
  }
  for (const std::string& m : missing) notes << "- missing, skipped: " << m << "\n";
  std::cout << stamp.str() << "\n\n" << table.str() << notes.str();

  const fsys::path dir(o.out);
  std::ofstream(dir / "brepmesh.md")
      << "# frontsteal vs Open CASCADE BRepMesh_IncrementalMesh on real CAD faces (measured)\n\n"
      << stamp.str() << "\n\n"
      << "Reproduce: `./build/release/tessellate/benchmarks/brepmesh_comparison --out tessellate/results`.\n\n"
      << "Deviation: distance from the triangle to the exact surface at the same (u, v), sampled at 12 barycentric "
         "points per triangle (the lattice of step 1/4 without the corners); max and mean over all samples, in model "
         "units. Both sides are measured on the faces frontsteal imported (\"compared\": faces that gave at least one surface; "
         "import_cad_file with its default 8 samples per p-curve span; pieces of a compared face that the importer rejected "
         "are missing on our side only); BRepMesh is timed on the whole shape, and on a compound of the compared faces "
         "alone where some faces were not imported. \"ours ms\" is "
         "planning + triangulation + the trimming audit of every imported surface; the import itself (once per file, "
         "like loading a model) is not included: it took "
      << [&] {
           std::ostringstream s;
           for (std::size_t k = 0; k < rows.size(); k += o.eps_fractions.size()) {
             s << (k ? ", " : "") << rows[k].file << " " << fmt(rows[k].import_ms) << " ms";
           }
           return s.str();
         }()
      << ". The deviation measure sees the interior error only, not how closely the trimmed boundary follows the "
         "true edges.\n\n"
      << table.str() << "\nPer row (measured):\n\n" << notes.str();
  {
    std::ofstream csv(dir / "brepmesh.csv");
    csv << "file,faces,faces_compared,surfaces,trimmed,diagonal,eps_fraction,eps,import_ms,ours_ms_median,ours_ms_min,"
           "ours_ms_max,occt_1t_ms_median,occt_1t_ms_min,occt_1t_ms_max,occt_par_ms_median,occt_par_ms_min,occt_par_ms_max,"
           "occt_1t_compared_ms_median,ours_triangles,occt_triangles_compared,occt_triangles_all,"
           "occt_triangles_default_angle,ours_capped,"
           "ours_inconsistencies,ours_dev_max,ours_dev_mean,occt_dev_max,occt_dev_mean,occt_status\n";
    csv << std::setprecision(9);
    for (const Row& r : rows) {
      csv << r.file << ',' << r.faces << ',' << r.faces_compared << ',' << r.surfaces << ',' << r.trimmed << ','
          << r.diagonal << ',' << r.eps_fraction << ',' << r.eps << ',' << r.import_ms << ',' << r.ours.median << ','
          << r.ours.min << ',' << r.ours.max << ',' << r.occt_serial.median << ',' << r.occt_serial.min << ','
          << r.occt_serial.max << ',' << r.occt_parallel.median << ',' << r.occt_parallel.min << ','
          << r.occt_parallel.max << ',' << (r.timed_imported_only ? r.occt_serial_imported.median : r.occt_serial.median)
          << ',' << r.our_triangles << ',' << r.occt_triangles << ',' << r.occt_triangles_all << ','
          << r.occt_triangles_default_angle << ',' << r.capped << ','
          << r.inconsistencies << ',' << r.our_dev.max << ',' << r.our_dev.mean() << ',' << r.occt_dev.max << ','
          << r.occt_dev.mean() << ',' << r.occt_status << '\n';
    }
  }
  {
    std::ofstream js(dir / "brepmesh.json");
    js << "{\n  \"kind\": \"measured\", \"date\": \"" << date << "\", \"machine\": \"" << frontsteal::cpu_model()
       << "\", \"hardware_threads\": " << std::thread::hardware_concurrency() << ", \"commit\": \"" << FRONTSTEAL_GIT_COMMIT
       << "\", \"load_average_before\": " << load_before << ", \"load_average_after\": " << load_after
       << ", \"repeats\": " << o.repeats << ", \"angle_rad\": " << o.angle << ", \"max_steps\": " << o.max_steps
       << ", \"time_unit\": \"ms\",\n  \"rows\": [\n";
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Row& r = rows[k];
      js << "    {\"file\": \"" << r.file << "\", \"faces\": " << r.faces << ", \"faces_compared\": " << r.faces_compared
         << ", \"surfaces\": " << r.surfaces << ", \"trimmed\": " << r.trimmed << ", \"diagonal\": " << fmt(r.diagonal, 9)
         << ", \"eps_fraction\": " << r.eps_fraction << ", \"eps\": " << fmt(r.eps, 9) << ", \"import_ms\": "
         << fmt(r.import_ms, 6) << ",\n     \"ours\": {\"ms\": " << timing_json(r.ours) << ", \"triangles\": "
         << r.our_triangles << ", \"capped\": " << r.capped << ", \"inconsistencies\": " << r.inconsistencies
         << ", \"dev_max\": " << fmt(r.our_dev.max, 6) << ", \"dev_mean\": " << fmt(r.our_dev.mean(), 6)
         << ", \"samples\": " << r.our_dev.samples << ", \"vertex_residual_max\": " << fmt(r.our_dev.vertex_max, 6) << "},\n     \"brepmesh\": {\"ms_1t\": " << timing_json(r.occt_serial)
         << ", \"ms_parallel\": " << timing_json(r.occt_parallel) << ", \"ms_1t_compared_faces\": "
         << (r.timed_imported_only ? timing_json(r.occt_serial_imported) : std::string("null"))
         << ", \"triangles_compared\": " << r.occt_triangles << ", \"triangles_all\": " << r.occt_triangles_all
         << ", \"triangles_parallel_compared\": " << r.occt_triangles_parallel
         << ", \"triangles_default_angle_compared\": " << r.occt_triangles_default_angle
         << ", \"edge_tolerance_max\": " << fmt(r.edge_tolerance, 6) << ", \"status\": " << r.occt_status
         << ", \"dev_max\": " << fmt(r.occt_dev.max, 6) << ", \"dev_mean\": " << fmt(r.occt_dev.mean(), 6)
         << ", \"samples\": " << r.occt_dev.samples << ", \"vertex_residual_max\": " << fmt(r.occt_dev.vertex_max, 6) << "}}" << (k + 1 < rows.size() ? "," : "") << "\n";
    }
    js << "  ]\n}\n";
  }
  return 0;
}
