// occt_import.cpp — STEP / IGES / BREP → Model through Open CASCADE 7.6 (see occt_import.hpp for the steps).
#include "tessellate/occt_import.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <GeomConvert_BSplineSurfaceToBezierSurface.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>

#include "tessellate/model_format.hpp"
#include "tessellate/trim_region.hpp"

namespace frontsteal::tess {
namespace {

namespace fsys = std::filesystem;

// Two consecutive (u, v) points closer than this (relative to the face's (u, v) extent) are one point.
constexpr double kDuplicateRelative = 1e-10;
// A gap between consecutive edges' p-curves (or between a loop's end and its start) up to this, relative to
// the face's (u, v) extent, is bridged by a straight segment; a larger one means the wire is not closed in
// (u, v) (e.g. a periodic face whose seam edge is missing) and the face is skipped.
constexpr double kMaxGapRelative = 1e-2;

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A surface name is one word in the native format: keep [A-Za-z0-9_.-], replace the rest.
std::string sanitize(const std::string& s) {
  std::string out;
  for (const char c : s)
    out += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ? c : '_';
  return out.empty() ? std::string("cad") : out;
}

std::string occt_message(const Standard_Failure& e) {
  const char* m = e.GetMessageString();
  std::string type = e.DynamicType()->Name();
  return (m != nullptr && *m != '\0') ? type + ": " + m : type;
}

// Open CASCADE's readers report progress and statistics through the default messenger (to stdout); an
// importer should not. For the guard's lifetime the messenger's printers are replaced by one that keeps the
// first failure message (to quote in an error) and prints nothing.
class QuietMessenger {
 public:
  QuietMessenger() : capture_(new CapturePrinter) {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    saved_ = m->Printers();
    m->ChangePrinters().Clear();
    m->AddPrinter(capture_);
  }
  ~QuietMessenger() {
    const Handle(Message_Messenger)& m = Message::DefaultMessenger();
    m->ChangePrinters() = saved_;
  }
  QuietMessenger(const QuietMessenger&) = delete;
  QuietMessenger& operator=(const QuietMessenger&) = delete;

  // " (Open CASCADE: <first failure message>)", or nothing.
  std::string first_failure() const {
    std::string m = capture_->first;
    while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back()))) m.pop_back();
    return m.empty() ? std::string() : " (Open CASCADE: " + m + ")";
  }

 private:
  class CapturePrinter : public Message_Printer {
   public:
    CapturePrinter() { SetTraceLevel(Message_Fail); }
    mutable std::string first;

   protected:
    void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override {
      if (gravity >= Message_Fail && first.empty()) first = text.ToCString();
    }
  };
  Message_SequenceOfPrinters saved_;
  Handle(CapturePrinter) capture_;
};

TopoDS_Shape read_shape(const std::string& path) {
  const std::string ext = lowercase(fsys::path(path).extension().string());
  const bool step = ext == ".step" || ext == ".stp";
  const bool iges = ext == ".iges" || ext == ".igs";
  const bool brep = ext == ".brep";
  if (!step && !iges && !brep) {
    throw std::runtime_error(path + ": unknown CAD file extension '" + ext +
                             "' (expected .step, .stp, .iges, .igs or .brep)");
  }
  std::error_code ec;
  if (fsys::is_directory(path, ec)) throw std::runtime_error(path + ": cannot open the file (it is a directory)");
  if (!fsys::exists(path, ec)) throw std::runtime_error(path + ": cannot open the file (no such file)");
  if (!fsys::is_regular_file(path, ec)) throw std::runtime_error(path + ": cannot open the file (not a regular file)");
  if (std::ifstream probe(path); !probe) throw std::runtime_error(path + ": cannot open the file (not readable)");

  const QuietMessenger quiet;
  try {
    if (step) {
      STEPControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
        throw std::runtime_error(path + ": not a readable STEP file" + quiet.first_failure());
      }
      reader.TransferRoots();
      if (reader.NbShapes() == 0)
        throw std::runtime_error(path + ": the STEP file holds no shape Open CASCADE could transfer");
      return reader.OneShape();
    }
    if (iges) {
      IGESControl_Reader reader;
      if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) {
        throw std::runtime_error(path + ": not a readable IGES file" + quiet.first_failure());
      }
      reader.TransferRoots();
      if (reader.NbShapes() == 0)
        throw std::runtime_error(path + ": the IGES file holds no shape Open CASCADE could transfer");
      return reader.OneShape();
    }
    BRep_Builder builder;
    TopoDS_Shape shape;
    // BRepTools::Read writes its complaints to std::cout: keep them for the error message instead.
    std::ostringstream said;
    std::streambuf* const cout_buf = std::cout.rdbuf(said.rdbuf());
    bool ok = false;
    try {
      ok = BRepTools::Read(shape, path.c_str(), builder);
    } catch (...) {
      std::cout.rdbuf(cout_buf);
      throw;
    }
    std::cout.rdbuf(cout_buf);
    if (!ok || shape.IsNull()) {
      std::string why = said.str();
      why.erase(std::remove(why.begin(), why.end(), '\n'), why.end());
      throw std::runtime_error(path + ": not a readable BREP file" +
                               (why.empty() ? quiet.first_failure() : " (Open CASCADE: " + why + ")"));
    }
    return shape;
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(path + ": Open CASCADE failed to read it: " + occt_message(e));
  }
}

// ---- trim loops --------------------------------------------------------------------------------------------

// Parameters where a p-curve's polynomial pieces meet inside [first, last], plus the two ends; and how many
// segments each piece gets (1 for a straight piece).
void pcurve_breaks(const Handle(Geom2d_Curve) & curve, double first, double last, int samples_per_span,
                   std::vector<double>& breaks, int& per_span) {
  Handle(Geom2d_Curve) basis = curve;
  while (const Handle(Geom2d_TrimmedCurve) t = Handle(Geom2d_TrimmedCurve)::DownCast(basis)) basis = t->BasisCurve();
  breaks.assign({first});
  per_span = samples_per_span;
  if (const Handle(Geom2d_BSplineCurve) bs = Handle(Geom2d_BSplineCurve)::DownCast(basis)) {
    if (bs->Degree() == 1) per_span = 1;
    const double period = bs->IsPeriodic() ? bs->LastParameter() - bs->FirstParameter() : 0.0;
    const double eps = 1e-12 * std::max(1.0, std::abs(last - first));
    for (int k = 1; k <= bs->NbKnots(); ++k) {
      double t = bs->Knot(k);
      if (period > 0) t += std::ceil((first - t) / period) * period;  // first copy at or after `first`
      for (; t < last - eps; t += period) {
        if (t > first + eps) breaks.push_back(t);
        if (period <= 0) break;
      }
    }
  } else if (Handle(Geom2d_Line)::DownCast(basis)) {
    per_span = 1;
  } else if (const Handle(Geom2d_BezierCurve) bz = Handle(Geom2d_BezierCurve)::DownCast(basis)) {
    if (bz->Degree() == 1) per_span = 1;
  } else {
    // Conics and other curves (not expected after NURBS conversion): four spans.
    for (int k = 1; k < 4; ++k) breaks.push_back(first + (last - first) * k / 4.0);
  }
  breaks.push_back(last);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
}

struct FaceLoops {
  std::vector<Polygon2> loops;
  std::string problem;  // non-empty: the face cannot be imported, and why
  double max_gap = 0;   // largest bridged gap, absolute
};

FaceLoops build_loops(const TopoDS_Face& face, int samples_per_span) {
  FaceLoops out;
  std::vector<std::vector<glm::dvec2>> raw;     // each loop's points as sampled, edges concatenated
  std::vector<std::vector<std::size_t>> joins;  // where each edge starts in `raw` (for the gap check)
  std::vector<double> breaks;
  for (TopExp_Explorer wires(face, TopAbs_WIRE); wires.More(); wires.Next()) {
    const TopoDS_Wire& wire = TopoDS::Wire(wires.Current());
    // An INTERNAL or EXTERNAL wire (an imprint, a seam of another shape) bounds nothing.
    if (wire.Orientation() == TopAbs_INTERNAL || wire.Orientation() == TopAbs_EXTERNAL) continue;
    std::vector<glm::dvec2> pts;
    std::vector<std::size_t> starts;
    for (BRepTools_WireExplorer we(wire, face); we.More(); we.Next()) {
      const TopoDS_Edge& edge = we.Current();
      if (edge.Orientation() == TopAbs_INTERNAL || edge.Orientation() == TopAbs_EXTERNAL) continue;
      double first = 0, last = 0;
      const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(edge, face, first, last);
      if (pc.IsNull()) {
        out.problem = "face: an edge has no p-curve on the face";
        return out;
      }
      int per_span = 1;
      pcurve_breaks(pc, first, last, samples_per_span, breaks, per_span);
      std::vector<glm::dvec2> edge_pts;
      for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
        for (int k = 0; k < per_span; ++k) {
          const double t = breaks[s] + (breaks[s + 1] - breaks[s]) * k / per_span;
          const gp_Pnt2d p = pc->Value(t);
          edge_pts.emplace_back(p.X(), p.Y());
        }
      }
      const gp_Pnt2d end = pc->Value(last);
      edge_pts.emplace_back(end.X(), end.Y());
      if (edge.Orientation() == TopAbs_REVERSED) std::reverse(edge_pts.begin(), edge_pts.end());
      starts.push_back(pts.size());
      pts.insert(pts.end(), edge_pts.begin(), edge_pts.end());
    }
    if (!pts.empty()) {
      raw.push_back(std::move(pts));
      joins.push_back(std::move(starts));
    }
  }
  if (raw.empty()) return out;  // a face without wires: its natural bounds (handled by the caller)

  // The face's (u, v) extent sets the tolerances.
  glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const auto& l : raw) {
    for (const glm::dvec2& p : l) lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(extent > 0) || !std::isfinite(extent)) {
    out.problem = "face: its trim loops have no extent in (u, v)";
    return out;
  }
  const double dup = kDuplicateRelative * extent;
  for (std::size_t l = 0; l < raw.size(); ++l) {
    const std::vector<glm::dvec2>& pts = raw[l];
    // Gaps: where an edge starts vs where the previous one ended, and the loop's closure.
    for (std::size_t e = 0; e < joins[l].size(); ++e) {
      const std::size_t s = joins[l][e];
      const glm::dvec2 prev_end = e == 0 ? pts.back() : pts[s - 1];
      out.max_gap = std::max(out.max_gap, glm::length(pts[s] - prev_end));
    }
    Polygon2 poly;
    for (const glm::dvec2& p : pts) {
      if (poly.empty() || glm::length(p - poly.back()) > dup) poly.push_back(p);
    }
    while (poly.size() > 1 && glm::length(poly.back() - poly.front()) <= dup) poly.pop_back();
    out.loops.push_back(std::move(poly));
  }
  if (out.max_gap > kMaxGapRelative * extent)
    out.problem = "face: a wire is not closed in (u, v) (a gap over 1% of the face's extent)";
  return out;
}

// Even-odd point-in-polygon.
bool inside(const Polygon2& poly, const glm::dvec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const glm::dvec2& a = poly[i];
    const glm::dvec2& b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

// Whether loop `a` lies inside loop `b`: majority vote of a few of a's vertices (loops may touch).
bool loop_inside(const Polygon2& a, const Polygon2& b) {
  const std::size_t probes = std::min<std::size_t>(7, a.size());
  std::size_t votes = 0;
  for (std::size_t k = 0; k < probes; ++k) votes += inside(b, a[k * a.size() / probes]) ? 1 : 0;
  return 2 * votes > probes;
}

// A coordinate within 10⁻⁵ of a cell of a grid line is put on it. split_region moves points lying on a line
// off it by 10⁻⁶ of a cell; a point left just beside the line (a p-curve sample a hair inside the face's
// boundary, say) could then end up on the wrong side of its moved neighbours and the piece would cross itself.
double snap_to_line(double x, const std::vector<double>& lines) {
  const auto it = std::lower_bound(lines.begin(), lines.end(), x);
  double best = x, best_d = std::numeric_limits<double>::max();
  for (auto k = it == lines.begin() ? it : it - 1; k != lines.end() && k <= it; ++k) {
    const std::size_t i = static_cast<std::size_t>(k - lines.begin());
    double cell = std::numeric_limits<double>::max();
    if (i > 0) cell = std::min(cell, lines[i] - lines[i - 1]);
    if (i + 1 < lines.size()) cell = std::min(cell, lines[i + 1] - lines[i]);
    const double d = std::abs(x - *k);
    if (d <= 1e-5 * cell && d < best_d) best = *k, best_d = d;
  }
  return best;
}

// Cuts off the small loops a polyline makes where consecutive p-curves overshoot each other at a corner
// (sloppy IGES/STEP p-curves, or a p-curve clamped onto the domain's edge): when segment i crosses segment
// i+d (d ≤ kWindow, and the cut-off part is the smaller one by vertex count), the vertices between them are
// replaced by the crossing point. Returns how many were cut. Only nearby segments are compared: a loop
// crossing itself far away is left for the model format's checks to report.
int cut_local_loops(Polygon2& poly) {
  constexpr std::size_t kWindow = 8;
  const auto orient = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  int cuts = 0;
  for (bool again = true; again && poly.size() >= 6;) {
    again = false;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n && !again; ++i) {
      const glm::dvec2 a = poly[i], b = poly[(i + 1) % n];
      for (std::size_t d = 2; d <= kWindow && 2 * d + 2 <= n && !again; ++d) {
        const std::size_t j = (i + d) % n;
        const glm::dvec2 c = poly[j], e = poly[(j + 1) % n];
        const double d1 = orient(a, b, c), d2 = orient(a, b, e), d3 = orient(c, e, a), d4 = orient(c, e, b);
        if (!(((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))) continue;
        const glm::dvec2 x = a + (b - a) * (d3 / (d3 - d4));
        Polygon2 out;
        out.reserve(n - d + 1);
        if (i + d < n) {  // drop i+1 .. i+d
          out.assign(poly.begin(), poly.begin() + static_cast<std::ptrdiff_t>(i + 1));
          out.push_back(x);
          out.insert(out.end(), poly.begin() + static_cast<std::ptrdiff_t>(i + d + 1), poly.end());
        } else {  // the dropped run wraps: keep j+1 .. i
          out.assign(poly.begin() + static_cast<std::ptrdiff_t>(j + 1),
                     poly.begin() + static_cast<std::ptrdiff_t>(i + 1));
          out.push_back(x);
        }
        poly = std::move(out);
        ++cuts;
        again = true;
      }
    }
  }
  return cuts;
}

// ---- patches -------------------------------------------------------------------------------------------

BezierPatch to_patch(const Handle(Geom_BezierSurface) & b) {
  BezierPatch p(b->UDegree(), b->VDegree());
  for (int i = 0; i <= p.degree_u; ++i) {
    for (int j = 0; j <= p.degree_v; ++j) {
      const gp_Pnt& q = b->Pole(i + 1, j + 1);
      p.set(i, j, glm::dvec3(q.X(), q.Y(), q.Z()), b->Weight(i + 1, j + 1));
    }
  }
  return p;
}

BezierPatch mirror_u(const BezierPatch& p) {
  BezierPatch m = p;
  for (int i = 0; i <= p.degree_u; ++i) {
    for (int j = 0; j <= p.degree_v; ++j) m.control[m.index(i, j)] = p.control[p.index(p.degree_u - i, j)];
  }
  return m;
}

// Removes spikes: a vertex where the ring turns straight back along the edge it came by (collinear, pointing
// back). The tracer's walk along a cell edge next to a chain lying on that edge (nudged 10⁻⁶ of a cell off it)
// leaves such zero-width spikes; they bound no area, and the native format refuses them as retraced edges
// (loop_validation.hpp), so 34 of bearing.iges's faces were lost before they were removed here.
void remove_spikes(Polygon2& q) {
  const auto spike = [](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
    const glm::dvec2 ab = b - a, bc = c - b;
    const double cross = ab.x * bc.y - ab.y * bc.x;
    return glm::dot(ab, bc) < 0 && std::abs(cross) <= 1e-12 * glm::length(ab) * glm::length(bc);
  };
  for (bool changed = true; changed && q.size() >= 3;) {
    changed = false;
    Polygon2 kept;
    kept.reserve(q.size());
    for (const glm::dvec2& p : q) {
      if (!kept.empty() && kept.back() == p) continue;
      kept.push_back(p);
      while (kept.size() >= 3 && spike(kept[kept.size() - 3], kept[kept.size() - 2], kept.back())) {
        kept.erase(kept.end() - 2);
        changed = true;
        if (kept.size() >= 2 && kept[kept.size() - 2] == kept.back()) kept.pop_back();
      }
    }
    // Across the wrap-around: the last point and the first two, the last two and the first.
    while (kept.size() >= 3 &&
           (spike(kept[kept.size() - 2], kept.back(), kept[0]) || spike(kept.back(), kept[0], kept[1]))) {
      if (spike(kept[kept.size() - 2], kept.back(), kept[0])) {
        kept.pop_back();
      } else {
        kept.erase(kept.begin());
      }
      changed = true;
    }
    while (kept.size() > 1 && kept.back() == kept.front()) kept.pop_back();
    q.swap(kept);
  }
}

// A ring of a cell's piece in the patch's [0,1]² (mirrored in u for a reversed face), as a chained polyline
// loop, spikes removed; empty when it degenerates to fewer than 3 points.
TrimLoop to_patch_loop(const Polygon2& ring, glm::dvec2 lo, glm::dvec2 hi, bool mirror) {
  Polygon2 q;
  q.reserve(ring.size());
  for (const glm::dvec2& p : ring) {
    glm::dvec2 t = glm::clamp((p - lo) / (hi - lo), glm::dvec2(0.0), glm::dvec2(1.0));
    if (mirror) t.x = 1.0 - t.x;
    if (q.empty() || glm::length(t - q.back()) > 1e-13) q.push_back(t);
  }
  while (q.size() > 1 && glm::length(q.back() - q.front()) <= 1e-13) q.pop_back();
  remove_spikes(q);
  TrimLoop loop;
  if (q.size() < 3) return loop;
  if (mirror) std::reverse(q.begin(), q.end());
  loop.segments.reserve(q.size());
  for (std::size_t k = 0; k < q.size(); ++k) loop.segments.push_back({{q[k], q[(k + 1) % q.size()]}});
  return loop;
}

// The native format's strict checks on one surface: empty when it passes, else the parser's reason.
std::string check_surface(const Surface& s) {
  Model m;
  m.surfaces.push_back(s);
  std::stringstream text;
  write_model(text, m);
  try {
    (void)parse_model(text, "check");
  } catch (const ModelError& e) {
    std::string reason = e.what();
    const std::string prefix = "check:" + std::to_string(e.line()) + ": ";
    if (reason.rfind(prefix, 0) == 0) reason.erase(0, prefix.size());
    return reason;
  }
  return {};
}

class FaceImporter {
 public:
  FaceImporter(std::string stem, const ImportOptions& options, Model& out, ImportReport& report)
      : stem_(std::move(stem)), options_(options), out_(out), report_(report) {}

  void import(const TopoDS_Face& face, int index, bool solid) {
    index_ = index;
    solid_ = solid;
    const std::size_t surfaces_before = out_.surfaces.size();
    const std::size_t skips_before = report_.skipped.size();
    const std::array<int, 4> counts_before = {report_.patches, report_.trim_loops, report_.loops_reoriented,
                                              report_.corner_loops_cut};
    // A face that fails half-way leaves nothing behind: its surfaces, skips and counts are taken back.
    const auto undo = [&] {
      out_.surfaces.resize(surfaces_before);
      report_.skipped.resize(skips_before);
      report_.patches = counts_before[0];
      report_.trim_loops = counts_before[1];
      report_.loops_reoriented = counts_before[2];
      report_.corner_loops_cut = counts_before[3];
    };
    std::string stage = "NURBS conversion";
    try {
      const bool reversed = face.Orientation() == TopAbs_REVERSED;
      BRepBuilderAPI_NurbsConvert convert(face, Standard_True);
      TopoDS_Shape converted = convert.Shape();
      if (converted.ShapeType() != TopAbs_FACE) {
        TopExp_Explorer f(converted, TopAbs_FACE);
        if (!f.More()) return skip("face: NURBS conversion gave no face");
        converted = f.Current();
      }
      const TopoDS_Face fwd = TopoDS::Face(converted.Oriented(TopAbs_FORWARD));

      stage = "B-spline surface";
      Handle(Geom_Surface) surface = BRep_Tool::Surface(fwd);
      if (surface.IsNull()) return skip("face: it has no surface");
      while (const Handle(Geom_RectangularTrimmedSurface) t =
                 Handle(Geom_RectangularTrimmedSurface)::DownCast(surface)) {
        surface = t->BasisSurface();
      }
      Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(surface);
      if (bspline.IsNull()) {
        const std::string type = surface->DynamicType()->Name();
        try {
          bspline = GeomConvert::SurfaceToBSplineSurface(surface);
        } catch (const Standard_Failure&) {
        }
        if (bspline.IsNull()) return skip("face: its " + type + " could not be converted to a B-spline surface");
      }
      if (bspline->UDegree() > kMaxDegree || bspline->VDegree() > kMaxDegree) {  // beyond Open CASCADE's own limit
        return skip("face: B-spline degree " + std::to_string(bspline->UDegree()) + "x" +
                    std::to_string(bspline->VDegree()) + " exceeds " + std::to_string(kMaxDegree));
      }

      stage = "trim loops";
      FaceLoops fl = build_loops(fwd, options_.samples_per_span);
      if (!fl.problem.empty()) return skip(fl.problem);

      stage = "patch grid";
      double U0 = 0, U1 = 0, V0 = 0, V1 = 0;
      bspline->Bounds(U0, U1, V0, V1);
      const bool natural = fl.loops.empty();  // no wire: the surface's own bounds
      glm::dvec2 lo(U0, V0), hi(U1, V1);
      if (!natural) {
        lo = glm::dvec2(std::numeric_limits<double>::max());
        hi = -lo;
        for (const Polygon2& l : fl.loops) {
          for (const glm::dvec2& p : l) lo = glm::min(lo, p), hi = glm::max(hi, p);
        }
        // A periodic direction is unrolled to the loops' range (at most one period); a bounded one is
        // clamped to the surface's bounds.
        // Ends within rounding of the surface's bounds are put on them (Segment would otherwise shift a
        // periodic range starting at −10⁻¹⁵ by a whole period).
        const auto near = [](double a, double b, double span) { return std::abs(a - b) <= 1e-9 * std::max(1.0, span); };
        if (near(lo.x, U0, U1 - U0)) lo.x = U0;
        if (near(hi.x, U1, U1 - U0)) hi.x = U1;
        if (near(lo.y, V0, V1 - V0)) lo.y = V0;
        if (near(hi.y, V1, V1 - V0)) hi.y = V1;
        if (bspline->IsUPeriodic()) {
          hi.x = std::min(hi.x, lo.x + bspline->UPeriod());
        } else {
          lo.x = std::max(lo.x, U0), hi.x = std::min(hi.x, U1);
        }
        if (bspline->IsVPeriodic()) {
          hi.y = std::min(hi.y, lo.y + bspline->VPeriod());
        } else {
          lo.y = std::max(lo.y, V0), hi.y = std::min(hi.y, V1);
        }
      }
      if (!(hi.x - lo.x > 1e-9 * std::max(1.0, std::abs(U1 - U0))) ||
          !(hi.y - lo.y > 1e-9 * std::max(1.0, std::abs(V1 - V0)))) {
        return skip("face: its (u, v) range is degenerate");
      }
      Handle(Geom_BSplineSurface) cut = Handle(Geom_BSplineSurface)::DownCast(bspline->Copy());
      const double snap_u = 1e-7 * (hi.x - lo.x), snap_v = 1e-7 * (hi.y - lo.y);
      if (!natural) cut->Segment(lo.x, hi.x, lo.y, hi.y, snap_u, snap_v);
      if (cut->IsUPeriodic()) cut->SetUNotPeriodic();
      if (cut->IsVPeriodic()) cut->SetVNotPeriodic();
      GeomConvert_BSplineSurfaceToBezierSurface split(cut);
      const int nu = split.NbUPatches(), nv = split.NbVPatches();
      TColStd_Array1OfReal uk(1, nu + 1), vk(1, nv + 1);
      split.UKnots(uk);
      split.VKnots(vk);
      std::vector<double> u_lines, v_lines;
      for (int k = uk.Lower(); k <= uk.Upper(); ++k) u_lines.push_back(uk(k));
      for (int k = vk.Lower(); k <= vk.Upper(); ++k) v_lines.push_back(vk(k));
      for (std::size_t k = 1; k < u_lines.size(); ++k) {
        if (!(u_lines[k] > u_lines[k - 1])) return skip("face: its knots in u are not strictly increasing");
      }
      for (std::size_t k = 1; k < v_lines.size(); ++k) {
        if (!(v_lines[k] > v_lines[k - 1])) return skip("face: its knots in v are not strictly increasing");
      }
      report_.patches += nu * nv;

      // A periodic direction may come out of Segment shifted by whole periods: the loops follow.
      const glm::dvec2 dlo(u_lines.front(), v_lines.front()), dhi(u_lines.back(), v_lines.back());
      const glm::dvec2 shift(bspline->IsUPeriodic() ? dlo.x - lo.x : 0.0, bspline->IsVPeriodic() ? dlo.y - lo.y : 0.0);
      if (!natural && shift != glm::dvec2(0.0)) {
        for (Polygon2& l : fl.loops) {
          for (glm::dvec2& p : l) p += shift;
        }
      }

      // Orientation by nesting; loops without area are dropped.
      const double area_floor = 1e-14 * (dhi.x - dlo.x) * (dhi.y - dlo.y);
      std::vector<Polygon2> loops;
      for (Polygon2& l : fl.loops) {
        for (glm::dvec2& p : l) p = glm::clamp(p, dlo, dhi);
        if (l.size() < 3 || std::abs(signed_area2(l)) <= area_floor) {
          skip("loop: it encloses no area in (u, v) (dropped)");
          continue;
        }
        loops.push_back(std::move(l));
      }
      report_.trim_loops += static_cast<int>(loops.size());
      if (!natural && loops.empty()) return skip("face: no trim loop encloses any area");
      for (std::size_t a = 0; a < loops.size(); ++a) {
        int depth = 0;
        for (std::size_t b = 0; b < loops.size(); ++b) depth += (a != b && loop_inside(loops[a], loops[b])) ? 1 : 0;
        const bool want_ccw = depth % 2 == 0;
        if ((signed_area2(loops[a]) > 0) != want_ccw) {
          std::reverse(loops[a].begin(), loops[a].end());
          ++report_.loops_reoriented;
        }
      }

      const auto snap = [&](Polygon2& l) {
        Polygon2 snapped;
        for (const glm::dvec2& p : l) {
          const glm::dvec2 q(snap_to_line(p.x, u_lines), snap_to_line(p.y, v_lines));
          if (snapped.empty() || q != snapped.back()) snapped.push_back(q);
        }
        while (snapped.size() > 1 && snapped.back() == snapped.front()) snapped.pop_back();
        l = std::move(snapped);
      };
      for (Polygon2& l : loops) {
        snap(l);
        if (cut_local_loops(l) > 0) {
          ++report_.corner_loops_cut;
          snap(l);
        }
      }

      stage = "region split";
      std::vector<CellCover> covers;
      if (natural) {
        covers.assign(static_cast<std::size_t>(nu * nv), CellCover{CellCover::Kind::full, {}});
      } else {
        covers = split_region(loops, u_lines, v_lines);
      }
      if (covers.size() != static_cast<std::size_t>(nu * nv))
        return skip("face: split_region returned a wrong number of cells");

      stage = "Bézier patches";
      for (int iu = 0; iu < nu; ++iu) {
        for (int iv = 0; iv < nv; ++iv) {
          const CellCover& cover = covers[static_cast<std::size_t>(iu * nv + iv)];
          if (cover.kind == CellCover::Kind::empty) continue;
          const int patch_index = iu * nv + iv;
          BezierPatch patch = to_patch(split.Patch(iu + 1, iv + 1));
          if (options_.planted_patch_shift) {
            glm::dvec3 lo_p(std::numeric_limits<double>::max()), hi_p = -lo_p;
            for (int i = 0; i <= patch.degree_u; ++i) {
              for (int j = 0; j <= patch.degree_v; ++j)
                lo_p = glm::min(lo_p, patch.point(i, j)), hi_p = glm::max(hi_p, patch.point(i, j));
            }
            const int i = patch.degree_u / 2, j = (patch.degree_v + 1) / 2;
            patch.set(i, j, patch.point(i, j) + glm::dvec3(1e-3 * glm::distance(lo_p, hi_p)), patch.weight(i, j));
          }
          for (int a = 0; a <= 4; ++a) {
            for (int b = 0; b <= 4; ++b) {
              const double s = a / 4.0, t = b / 4.0;
              const gp_Pnt q = cut->Value(u_lines[iu] + s * (u_lines[iu + 1] - u_lines[iu]),
                                          v_lines[iv] + t * (v_lines[iv + 1] - v_lines[iv]));
              const double error = glm::distance(evaluate(patch, s, t).position, glm::dvec3(q.X(), q.Y(), q.Z()));
              report_.max_patch_error = std::max(report_.max_patch_error, error);
            }
          }
          if (reversed) patch = mirror_u(patch);
          const std::string name = stem_ + "_f" + std::to_string(index_) + "_p" + std::to_string(patch_index);
          if (cover.kind == CellCover::Kind::full) {
            emit(make_surface(name, patch));
            continue;
          }
          const glm::dvec2 clo(u_lines[iu], v_lines[iv]), chi(u_lines[iu + 1], v_lines[iv + 1]);
          for (std::size_t k = 0; k < cover.pieces.size(); ++k) {
            const RegionPiece& piece = cover.pieces[k];
            Surface s = make_surface(cover.pieces.size() > 1 ? name + "_" + std::to_string(k) : name, patch);
            s.loops.push_back(to_patch_loop(piece.outer, clo, chi, reversed));
            if (s.loops.back().segments.empty()) {
              skip("piece: its outer boundary degenerates in the patch's domain");
              continue;
            }
            for (const Polygon2& h : piece.holes) {
              s.loops.push_back(to_patch_loop(h, clo, chi, reversed));
              if (s.loops.back().segments.empty()) s.loops.pop_back();  // a hole without area: no hole
            }
            emit(std::move(s));
          }
        }
      }
    } catch (const Standard_Failure& e) {
      undo();
      return skip("face: Open CASCADE failed (" + stage + "): " + occt_message(e));
    } catch (const std::exception& e) {
      undo();
      return skip("face: failed (" + stage + "): " + e.what());
    }
    const std::size_t made = out_.surfaces.size() - surfaces_before;
    if (made > 0) {
      ++report_.faces_imported;
      report_.surfaces += static_cast<int>(made);
    } else if (report_.skipped.size() == skips_before) {
      skip("face: its trim region covers no patch");
    }
  }

 private:
  void skip(std::string reason) { report_.skipped.push_back({index_, std::move(reason)}); }

  Surface make_surface(std::string name, const BezierPatch& patch) const {
    Surface s;
    s.name = std::move(name);
    s.patch = patch;
    s.solid = solid_;
    return s;
  }

  void emit(Surface s) {
    const std::string problem = check_surface(s);
    if (!problem.empty()) return skip("piece: rejected by the model format: " + problem);
    out_.surfaces.push_back(std::move(s));
  }

  std::string stem_;
  const ImportOptions& options_;
  Model& out_;
  ImportReport& report_;
  int index_ = 0;
  bool solid_ = false;
};

}  // namespace

// A STEP file ends with "END-ISO-10303-21;", an IGES file with its terminate section (a line whose column 73
// is 'T'). Without them the file was probably cut short, and the readers import what they got without a word.
std::string truncation_warning(const std::string& path) {
  const std::string ext = lowercase(fsys::path(path).extension().string());
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  std::string text(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(text.data(), tail);
  if (ext == ".step" || ext == ".stp") {
    if (text.find("END-ISO-10303-21") == std::string::npos) {
      return "the STEP file has no END-ISO-10303-21 trailer: it was probably cut short, and only part of it was read";
    }
  } else if (ext == ".iges" || ext == ".igs") {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    const std::size_t start = text.find_last_of('\n') == std::string::npos ? 0 : text.find_last_of('\n') + 1;
    const std::string last = text.substr(start);
    if (last.size() < 73 || last[72] != 'T') {
      return "the IGES file has no terminate section: it was probably cut short, and only part of it was read";
    }
  }
  return {};
}

ImportReport import_cad_file(const std::string& path, Model& out, const ImportOptions& options) {
  if (options.samples_per_span < 1) throw std::invalid_argument("ImportOptions::samples_per_span must be >= 1");
  const TopoDS_Shape shape = read_shape(path);
  ImportReport report;
  report.file = path;
  if (std::string w = truncation_warning(path); !w.empty()) report.warnings.push_back(std::move(w));
  const std::string stem = sanitize(fsys::path(path).stem().string());
  if (out.name.empty()) out.name = stem;

  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  report.faces = faces.Extent();
  // Faces of closed shells inside solids: their (composed) orientation makes the normals point outwards.
  std::vector<char> in_solid(static_cast<std::size_t>(faces.Extent()), 0);
  for (TopExp_Explorer solids(shape, TopAbs_SOLID); solids.More(); solids.Next()) {
    for (TopExp_Explorer shells(solids.Current(), TopAbs_SHELL); shells.More(); shells.Next()) {
      if (!BRep_Tool::IsClosed(shells.Current())) continue;
      for (TopExp_Explorer f(shells.Current(), TopAbs_FACE); f.More(); f.Next()) {
        const int k = faces.FindIndex(f.Current());
        if (k > 0) in_solid[static_cast<std::size_t>(k - 1)] = 1;
      }
    }
  }

  const QuietMessenger quiet;
  FaceImporter importer(stem, options, out, report);
  for (int k = 1; k <= faces.Extent(); ++k) {
    importer.import(TopoDS::Face(faces(k)), k - 1, in_solid[static_cast<std::size_t>(k - 1)] != 0);
  }
  return report;
}

}  // namespace frontsteal::tess
