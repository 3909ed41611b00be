// The Open CASCADE importer (tessellate/occt_import.hpp). Built only when CMake finds Open CASCADE.
//
// Shapes made here with OCCT's own primitives (box, cylinder, cone, sphere, torus, a box with a hole) are
// written to temporary .brep files and imported: the imported trimmed surfaces must have the shape's area and
// volume (integrated over each surface's trimmed region; OCCT's BRepGProp is the reference), which checks the
// trim loops, their split among the Bézier patches and the orientation of reversed faces at once. Real CAD
// files from Debian packages (bootstrap.sh installs them) are imported when present; when a
// file is missing the test says which package has it and goes on. Bad input must throw a clear error. No test
// touches the network.
#include "tessellate/occt_import.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pnt.hxx>

#include "tessellate/bezier_patch.hpp"
#include "tessellate/model_format.hpp"

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// A scratch folder, removed at the end.
struct TempDir {
  fsys::path path;
  TempDir() {
    static int counter = 0;
    path = fsys::temp_directory_path() /
           ("frontsteal_occt_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fsys::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fsys::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// ∫∫ over a surface's trimmed region of f(S(u,v)) du dv, by Green's theorem: ∮ F dv over the loops, with
// F(u, v) = ∫_0^u f(s, v) ds. Both integrals by 8-point Gauss–Legendre; loops as sampled polygons.
constexpr std::array<double, 8> kGaussX = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                           0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                           0.8983332387068134, 0.9801449282487681};
constexpr std::array<double, 8> kGaussW = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                           0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                           0.1111905172266872, 0.0506142681451881};

using Integrand = std::function<double(const ts::SurfacePoint&)>;

double region_integral(const ts::Surface& s, const Integrand& f) {
  const auto F = [&](glm::dvec2 p) {
    double sum = 0;
    for (std::size_t k = 0; k < kGaussX.size(); ++k)
      sum += kGaussW[k] * f(ts::evaluate(s.patch, p.x * kGaussX[k], p.y));
    return p.x * sum;
  };
  std::vector<std::vector<glm::dvec2>> polys;
  if (s.loops.empty()) {
    polys.push_back({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  } else {
    for (const ts::TrimLoop& loop : s.loops) polys.push_back(ts::sample_loop(loop, 32));
  }
  double total = 0;
  for (const auto& poly : polys) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const glm::dvec2 a = poly[i], b = poly[(i + 1) % poly.size()];
      if (a.y == b.y) continue;
      double seg = 0;
      for (std::size_t k = 0; k < kGaussX.size(); ++k) seg += kGaussW[k] * F(a + (b - a) * kGaussX[k]);
      total += seg * (b.y - a.y);
    }
  }
  return total;
}

double area(const ts::Surface& s) {
  return region_integral(s, [](const ts::SurfacePoint& p) { return glm::length(glm::cross(p.du, p.dv)); });
}
// (1/3) ∫∫ S · (S_u × S_v): summed over a closed surface with outward normals, the enclosed volume.
double volume_part(const ts::Surface& s) {
  return region_integral(s,
                         [](const ts::SurfacePoint& p) { return glm::dot(p.position, glm::cross(p.du, p.dv)) / 3.0; });
}

int face_of(const ts::Surface& s) {
  static const std::regex pattern(R"(.*_f([0-9]+)_p[0-9]+(_[0-9]+)?)");
  std::smatch m;
  REQUIRE(std::regex_match(s.name, m, pattern));
  return std::stoi(m[1].str());
}

// The model survives the native format's strict parser unchanged in size.
void require_round_trip(const ts::Model& model) {
  std::stringstream text;
  ts::write_model(text, model);
  ts::Model back;
  REQUIRE_NOTHROW(back = ts::parse_model(text, "round-trip"));
  REQUIRE(back.surfaces.size() == model.surfaces.size());
}

std::string describe(const ts::ImportReport& r) {
  std::ostringstream o;
  o << fsys::path(r.file).filename().string() << ": faces " << r.faces << ", imported " << r.faces_imported
    << ", patches " << r.patches << ", surfaces " << r.surfaces << ", loops " << r.trim_loops << ", reoriented "
    << r.loops_reoriented << ", corner loops cut " << r.corner_loops_cut << ", skipped " << r.skipped.size();
  std::map<std::string, int> reasons;
  for (const ts::ImportSkip& s : r.skipped) ++reasons[s.reason];
  for (const auto& [reason, n] : reasons) o << "\n    " << n << " x " << reason;
  return o.str();
}

// Open CASCADE's readers print statistics through the default messenger: quiet while reading references.
struct QuietReaders {
  std::vector<std::pair<Handle(Message_Printer), Message_Gravity>> saved;
  QuietReaders() {
    for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More(); it.Next()) {
      saved.emplace_back(it.Value(), it.Value()->GetTraceLevel());
      it.Value()->SetTraceLevel(Message_Fail);
    }
  }
  ~QuietReaders() {
    for (auto& [printer, level] : saved) printer->SetTraceLevel(level);
  }
};

TopoDS_Shape read_reference(const std::string& path) {
  const QuietReaders quiet;
  const std::string ext = fsys::path(path).extension().string();
  if (ext == ".brep") {
    TopoDS_Shape s;
    BRep_Builder b;
    BRepTools::Read(s, path.c_str(), b);
    return s;
  }
  if (ext == ".igs" || ext == ".iges") {
    IGESControl_Reader r;
    r.ReadFile(path.c_str());
    r.TransferRoots();
    return r.OneShape();
  }
  STEPControl_Reader r;
  r.ReadFile(path.c_str());
  r.TransferRoots();
  return r.OneShape();
}

// OCCT's area of the faces the importer took whole (no skip of any kind), and ours of their surfaces.
struct AreaCheck {
  double occt = 0, ours = 0;
  int faces = 0;
};
AreaCheck compare_area(const TopoDS_Shape& shape, const ts::ImportReport& report, const ts::Model& model) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  std::set<int> partial;
  for (const ts::ImportSkip& s : report.skipped) partial.insert(s.face);
  std::set<int> whole;
  for (const ts::Surface& s : model.surfaces) {
    if (!partial.count(face_of(s))) whole.insert(face_of(s));
  }
  AreaCheck c;
  for (const int f : whole) {
    GProp_GProps props;
    BRepGProp::SurfaceProperties(faces(f + 1), props);
    c.occt += props.Mass();
    ++c.faces;
  }
  for (const ts::Surface& s : model.surfaces) {
    if (whole.count(face_of(s))) c.ours += area(s);
  }
  return c;
}

struct Primitive {
  const char* name;
  TopoDS_Shape shape;
};

std::vector<Primitive> primitives() {
  std::vector<Primitive> out;
  out.push_back({"box", BRepPrimAPI_MakeBox(gp_Pnt(-1, 2, 3), 10, 20, 30).Shape()});
  out.push_back({"cylinder", BRepPrimAPI_MakeCylinder(5, 12).Shape()});
  out.push_back({"cone", BRepPrimAPI_MakeCone(4, 2, 6).Shape()});
  out.push_back({"sphere", BRepPrimAPI_MakeSphere(gp_Pnt(1, 2, 3), 7).Shape()});
  out.push_back({"torus", BRepPrimAPI_MakeTorus(10, 3).Shape()});
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape();
  const TopoDS_Shape drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(2, 1, -1), gp::DZ()), 4, 12).Shape();
  BRepAlgoAPI_Cut cut(block, drill);
  cut.Build();
  out.push_back({"block_with_hole", cut.Shape()});
  return out;
}

}  // namespace

TEST_CASE("occt import: primitives keep their area and volume with outward normals", "[occt]") {
  TempDir dir;
  for (const Primitive& prim : primitives()) {
    CAPTURE(prim.name);
    REQUIRE_FALSE(prim.shape.IsNull());
    const std::string path = dir.file(std::string(prim.name) + ".brep");
    REQUIRE(BRepTools::Write(prim.shape, path.c_str()));

    ts::Model model;
    const ts::ImportReport report = ts::import_cad_file(path, model, {.samples_per_span = 32});
    INFO(describe(report));
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(prim.shape, TopAbs_FACE, faces);
    CHECK(report.faces == faces.Extent());
    CHECK(report.faces_imported == report.faces);
    CHECK(report.skipped.empty());
    CHECK(report.surfaces == static_cast<int>(model.surfaces.size()));
    REQUIRE(!model.surfaces.empty());
    require_round_trip(model);

    GProp_GProps surface_props, volume_props;
    BRepGProp::SurfaceProperties(prim.shape, surface_props);
    BRepGProp::VolumeProperties(prim.shape, volume_props);
    double our_area = 0, our_volume = 0;
    for (const ts::Surface& s : model.surfaces) {
      our_area += area(s);
      our_volume += volume_part(s);
      CHECK(s.solid);
    }
    CHECK(our_area == Approx(surface_props.Mass()).epsilon(2e-3));
    // Positive and right: every face's S_u × S_v points out of the solid (reversed faces were mirrored).
    CHECK(our_volume == Approx(volume_props.Mass()).epsilon(2e-3));
  }
}

TEST_CASE("occt import: a holed face is split among its patches with the hole kept", "[occt]") {
  TempDir dir;
  const std::string path = dir.file("block.brep");
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(-10, -10, 0), 20, 20, 10).Shape();
  const TopoDS_Shape drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(2, 1, -1), gp::DZ()), 4, 12).Shape();
  REQUIRE(BRepTools::Write(BRepAlgoAPI_Cut(block, drill).Shape(), path.c_str()));
  ts::Model model;
  const ts::ImportReport report = ts::import_cad_file(path, model);
  INFO(describe(report));
  // The top and bottom faces: 400 − 16π each, whatever the split.
  double top = 0, bottom = 0;
  for (const ts::Surface& s : model.surfaces) {
    const ts::SurfacePoint p = ts::evaluate(s.patch, 0.5, 0.5);
    if (std::abs(p.position.z - 10) < 1e-9 && std::abs(p.normal.z - 1) < 1e-9) top += area(s);
    if (std::abs(p.position.z) < 1e-9 && std::abs(p.normal.z + 1) < 1e-9) bottom += area(s);
  }
  const double expected = 400 - 16 * M_PI;
  // The hole's p-curve is sampled with 8 segments per span: its polygon is a little smaller than the circle.
  CHECK(top == Approx(expected).epsilon(3e-3));
  CHECK(bottom == Approx(expected).epsilon(3e-3));
  CHECK(report.trim_loops >= 2 + 4 + 2);  // the holed faces have two loops each
}

TEST_CASE("occt import: a reversed face gets the opposite normal", "[occt]") {
  TempDir dir;
  const TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(5).Shape();
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(sphere, TopAbs_FACE, faces);
  REQUIRE(faces.Extent() == 1);
  const TopoDS_Shape face = faces(1);
  double flux[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const std::string path = dir.file(k == 0 ? "face.brep" : "face_reversed.brep");
    REQUIRE(BRepTools::Write(k == 0 ? face.Oriented(TopAbs_FORWARD) : face.Oriented(TopAbs_REVERSED), path.c_str()));
    ts::Model model;
    const ts::ImportReport report = ts::import_cad_file(path, model);
    INFO(describe(report));
    REQUIRE(report.faces_imported == 1);
    require_round_trip(model);
    for (const ts::Surface& s : model.surfaces) flux[k] += volume_part(s);
  }
  // Sphere of radius 5: ±(4/3)π·125 (the sign: which way the normals point).
  const double v = 4.0 / 3.0 * M_PI * 125;
  CHECK(std::abs(flux[0]) == Approx(v).epsilon(1e-3));
  CHECK(flux[1] == Approx(-flux[0]).epsilon(1e-9));
}

TEST_CASE("occt import: real CAD files from Debian packages", "[occt]") {
  struct Sample {
    std::string path;
    std::string package;
    int faces_imported;  // at least this many (Debian 12's files): a drop is a regression, not noise
  };
  // Every face of these files (Top.brep's 67 faces of degree 8 to 11 and bearing's degree-8 face included). A
  // stricter native check once refused 33 of bearing's faces (spikes in the pieces' rings) and no test noticed:
  // hence these counts.
  const std::vector<Sample> samples = {
      {"/usr/share/opencascade/data/iges/bearing.iges", "occt-misc", 213},
      {"/usr/share/opencascade/data/occ/Top.brep", "occt-misc", 324},
      {"/usr/share/opencascade/data/occ/hammer.brep", "occt-misc", 45},
      {"/usr/share/doc/calculix-cgx-examples/examples/cad/halter.igs", "calculix-cgx-examples", 105},
      {"/usr/share/doc/gmsh-doc/doc/gmsh/tutorial/t20_data.step.gz", "gmsh-doc", 21},
  };
  TempDir dir;
  int imported = 0;
  for (const Sample& sample : samples) {
    if (!fsys::exists(sample.path)) {
      WARN(sample.path << " is missing: install the Debian package " << sample.package
                       << " (bootstrap.sh installs it); not imported");
      continue;
    }
    std::string path = sample.path;
    if (fsys::path(path).extension() == ".gz") {
      path = dir.file(fsys::path(path).stem().string());
      const std::string cmd = "gzip -dc '" + sample.path + "' > '" + path + "'";
      if (std::system(cmd.c_str()) != 0) {
        WARN("could not decompress " << sample.path << " with gzip; not imported");
        continue;
      }
    }
    CAPTURE(path);
    ts::Model model;
    const ts::ImportReport report = ts::import_cad_file(path, model);
    std::cout << "occt_import_test: " << describe(report) << "\n";
    CHECK(report.faces > 0);
    CHECK(report.surfaces > 0);
    CHECK(report.surfaces == static_cast<int>(model.surfaces.size()));
    CHECK(report.faces_imported >= sample.faces_imported);
    // The patches are Open CASCADE's surface, checked by its own evaluator: within rounding of the model's size
    // (these files' extents are 1 to 1000 units).
    INFO("largest distance of a patch from Open CASCADE's surface: " << report.max_patch_error);
    CHECK(report.max_patch_error < 1e-8);
    // Every surface valid in the native format: loops closed, inside [0,1]², oriented, not self-intersecting.
    require_round_trip(model);
    // The faces taken whole have OCCT's area (up to the p-curves' sampling).
    const AreaCheck c = compare_area(read_reference(path), report, model);
    std::cout << "occt_import_test:   area of the " << c.faces << " faces imported whole: ours " << c.ours
              << ", Open CASCADE " << c.occt << " (ratio " << c.ours / c.occt << ")\n";
    CHECK(c.ours == Approx(c.occt).epsilon(1e-2));
    ++imported;
  }
  if (imported == 0) {
    WARN(
        "no real CAD file found: run ./bootstrap.sh (Debian packages occt-misc, "
        "calculix-cgx-examples, gmsh-doc)");
    return;
  }
}

TEST_CASE("negative control: a patch moved off Open CASCADE's surface shows in max_patch_error", "[occt]") {
  const std::string path = "/usr/share/opencascade/data/occ/Top.brep";
  if (!fsys::exists(path)) {
    WARN(path << " is missing: install the Debian package occt-misc (bootstrap.sh installs it)");
    return;
  }
  ts::Model exact, shifted;
  ts::ImportOptions planted;
  planted.planted_patch_shift = true;
  const ts::ImportReport good = ts::import_cad_file(path, exact);
  const ts::ImportReport bad = ts::import_cad_file(path, shifted, planted);
  INFO("max_patch_error " << good.max_patch_error << " exact, " << bad.max_patch_error << " with the planted shift");
  CHECK(good.max_patch_error < 1e-8);
  CHECK(bad.max_patch_error > 1e-6);
}

TEST_CASE("occt import: bad input throws a clear error", "[occt]") {
  TempDir dir;
  ts::Model model;
  SECTION("unknown extension") {
    const std::string path = dir.file("part.obj");
    std::ofstream(path) << "v 0 0 0\n";
    REQUIRE_THROWS_WITH(ts::import_cad_file(path, model),
                        Contains("unknown CAD file extension '.obj'") && Contains(path));
  }
  SECTION("missing file") {
    const std::string path = dir.file("missing.step");
    REQUIRE_THROWS_WITH(ts::import_cad_file(path, model), Contains("cannot open") && Contains(path));
  }
  SECTION("garbage, by each reader") {
    for (const char* name : {"garbage.step", "garbage.STP", "garbage.iges", "garbage.igs", "garbage.brep"}) {
      CAPTURE(name);
      const std::string path = dir.file(name);
      std::ofstream(path) << "this is not a CAD file\n\x01\x02\x03 garbage garbage\n";
      try {
        ts::import_cad_file(path, model);
        FAIL("no exception for " << path);
      } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        CHECK_THAT(what, Contains(path));
        CHECK((what.find("not a readable") != std::string::npos || what.find("holds no shape") != std::string::npos ||
               what.find("failed to read") != std::string::npos));
      }
    }
  }
  SECTION("bad options") {
    TempDir d2;
    const std::string path = d2.file("box.brep");
    REQUIRE(BRepTools::Write(BRepPrimAPI_MakeBox(1, 1, 1).Shape(), path.c_str()));
    REQUIRE_THROWS_AS(ts::import_cad_file(path, model, {.samples_per_span = 0}), std::invalid_argument);
  }
  CHECK(model.surfaces.empty());  // nothing half-imported
}
