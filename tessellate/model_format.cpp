// model_format.cpp — the strict parser and the writer of the native model format (see model_format.hpp).
#include "tessellate/model_format.hpp"

#include "tessellate/loop_validation.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <istream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace frontsteal::tess {
namespace {

constexpr double kClosureTolerance = 1e-9;

class Parser {
 public:
  Parser(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

  Model parse() {
    if (!next() || words_.size() != 2 || words_[0] != "frontsteal-model" || words_[1] != "1") {
      fail("expected the header 'frontsteal-model 1'");
    }
    Model model;
    std::vector<int> component_lines;  // line of each surface's 'component', 0 when it has none
    while (next()) {
      const std::string_view key = words_[0];
      if (key == "model") {
        if (!model.surfaces.empty()) fail("'model' must come before the first surface");
        expect_fields(2, "model <name>");
        model.name = words_[1];
      } else if (key == "surface") {
        if (words_.size() > 2) fail("'surface' takes at most a name");
        component_line_ = 0;
        model.surfaces.push_back(parse_surface(words_.size() == 2 ? std::string(words_[1]) : std::string()));
        component_lines.push_back(component_line_);
      } else {
        fail("unknown keyword '" + std::string(key) + "' (expected model or surface)");
      }
    }
    // Component ids index per-component arrays (rendering): they must be below the number of surfaces.
    for (std::size_t k = 0; k < model.surfaces.size(); ++k) {
      if (model.surfaces[k].component >= static_cast<int>(model.surfaces.size())) {
        throw ModelError(file_, component_lines[k],
                         "component " + std::to_string(model.surfaces[k].component) + " is out of range: a model of " +
                             std::to_string(model.surfaces.size()) + " surfaces has components 0.." +
                             std::to_string(model.surfaces.size() - 1));
      }
    }
    return model;
  }

 private:
  // Reads the next non-blank, non-comment line into words_; false at end of input.
  bool next() {
    std::string raw;
    while (std::getline(in_, raw)) {
      ++line_;
      check_bytes(raw);
      line_text_ = raw.substr(0, raw.find('#'));
      words_.clear();
      std::istringstream tokens(line_text_);
      for (std::string w; tokens >> w;) words_.push_back(w);
      if (!words_.empty()) return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& reason) const { throw ModelError(file_, line_, reason); }

  // Name what is wrong with the bytes themselves, before any word is read: otherwise a byte-order mark, a
  // CR-only file or a binary file would be reported as a missing header or "not a number".
  void check_bytes(const std::string& raw) const {
    if (line_ == 1 && raw.starts_with("\xEF\xBB\xBF")) {
      fail("the file starts with a UTF-8 byte-order mark (EF BB BF); save it as plain UTF-8/ASCII without one");
    }
    if (const auto nul = raw.find('\0'); nul != std::string::npos) {
      fail("NUL byte at column " + std::to_string(nul + 1) + ": this is a binary file, not a frontsteal model");
    }
    if (const auto cr = raw.find('\r'); cr != std::string::npos && cr + 1 < raw.size()) {
      fail("carriage return inside a line (column " + std::to_string(cr + 1) +
           "): the file uses CR-only line ends (classic Mac OS); convert them to LF");
    }
    if (raw.size() > kMaxLineLength) fail("line is longer than " + std::to_string(kMaxLineLength) + " bytes");
  }

  void expect_fields(std::size_t n, const char* form) const {
    if (words_.size() != n) fail("expected '" + std::string(form) + "'");
  }

  double number(std::size_t k, const char* what) const {
    const std::string& w = words_[k];
    double v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec == std::errc::result_out_of_range && end == w.data() + w.size()) {
      fail(std::string(what) + " '" + w + "' is out of the range of a double");
    }
    if (ec != std::errc{} || end != w.data() + w.size()) fail(std::string(what) + " '" + w + "' is not a number");
    if (!std::isfinite(v)) fail(std::string(what) + " '" + w + "' is not finite");
    return v;
  }

  int integer(std::size_t k, const char* what, int lo, int hi) const {
    const std::string& w = words_[k];
    int v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec == std::errc::result_out_of_range && end == w.data() + w.size()) {
      fail(std::string(what) + " " + w + " is out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    if (ec != std::errc{} || end != w.data() + w.size()) fail(std::string(what) + " '" + w + "' is not a whole number");
    if (v < lo || v > hi) {
      fail(std::string(what) + " " + w + " is out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    }
    return v;
  }

  bool next_in(const char* block) {
    if (!next()) fail(std::string("the file ends inside a '") + block + "' block");
    return true;
  }

  Surface parse_surface(std::string name) {
    Surface s;
    s.name = std::move(name);
    bool have_patch = false;
    int points_expected = 0;
    int points_read = 0;
    while (next_in("surface")) {
      const std::string_view key = words_[0];
      if (key == "endsurface") {
        if (!have_patch) fail("surface has no 'patch'");
        if (points_read != points_expected) {
          fail("surface ends after " + std::to_string(points_read) + " of " + std::to_string(points_expected) +
               " control points");
        }
        check_loops(s);
        return s;
      } else if (key == "solid") {
        expect_fields(1, "solid");
        s.solid = true;
      } else if (key == "component") {
        expect_fields(2, "component <k>");
        s.component = integer(1, "component", 0, std::numeric_limits<int>::max());
        component_line_ = line_;
      } else if (key == "patch") {
        if (have_patch) fail("a surface has exactly one 'patch'");
        expect_fields(3, "patch <degree_u> <degree_v>");
        const int du = integer(1, "degree", 1, kMaxDegree);
        const int dv = integer(2, "degree", 1, kMaxDegree);
        s.patch = BezierPatch(du, dv);
        have_patch = true;
        points_expected = (du + 1) * (dv + 1);
      } else if (key == "cp") {
        if (!have_patch) fail("'cp' before 'patch'");
        if (words_.size() != 4 && words_.size() != 5) fail("expected 'cp <x> <y> <z> [<w>]'");
        if (points_read == points_expected) {
          fail("more than the " + std::to_string(points_expected) + " control points a degree " +
               std::to_string(s.patch.degree_u) + "x" + std::to_string(s.patch.degree_v) + " patch has");
        }
        const glm::dvec3 p{number(1, "x"), number(2, "y"), number(3, "z")};
        const double w = words_.size() == 5 ? number(4, "weight") : 1.0;
        if (!(w > 0)) fail("weight " + words_[4] + " must be > 0");
        for (int c = 0; c < 3; ++c) {
          if (std::abs(p[c]) > kMaxCoordinate) {
            fail(std::string("xyz").substr(static_cast<std::size_t>(c), 1) + " " +
                 words_[1 + static_cast<std::size_t>(c)] +
                 " is out of range: |coordinate| <= " + format_limit(kMaxCoordinate) + " (step sizes square lengths)");
          }
        }
        if (w < kMinWeight || w > kMaxWeight) {
          fail("weight " + words_[4] + " is out of range " + format_limit(kMinWeight) + ".." +
               format_limit(kMaxWeight));
        }
        const int i = points_read / (s.patch.degree_v + 1);
        const int j = points_read % (s.patch.degree_v + 1);
        s.patch.set(i, j, p, w);
        ++points_read;
      } else if (key == "loop") {
        expect_fields(1, "loop");
        s.loops.push_back(parse_loop());
      } else {
        fail("unknown keyword '" + std::string(key) + "' in a surface (component, solid, patch, cp, loop, endsurface)");
      }
    }
    return s;  // unreachable: next_in fails at end of input
  }

  TrimLoop parse_loop() {
    TrimLoop loop;
    const int loop_line = line_;
    while (next_in("loop")) {
      const std::string_view key = words_[0];
      if (key == "endloop") {
        if (loop.segments.empty()) fail("empty loop");
        const glm::dvec2 first = loop.segments.front().control.front();
        const glm::dvec2 last = loop.segments.back().control.back();
        if (glm::length(first - last) > kClosureTolerance) {
          std::ostringstream gap;
          gap << "loop starting at line " << loop_line << " is not closed: it ends at (" << last.x << ", " << last.y
              << ") but starts at (" << first.x << ", " << first.y << ")";
          fail(gap.str());
        }
        loop_lines_.push_back(loop_line);
        return loop;
      } else if (key == "curve" || key == "polyline") {
        expect_fields(2, key == "curve" ? "curve <degree>" : "polyline <count>");
        const bool curve = key == "curve";
        const int n = curve ? integer(1, "curve degree", 1, kMaxDegree) + 1 : integer(1, "polyline count", 2, 1 << 20);
        std::vector<glm::dvec2> pts;
        for (int k = 0; k < n; ++k) {
          next_in("loop");
          if (words_[0] != "pt")
            fail("expected 'pt <u> <v>' (" + std::to_string(k) + " of " + std::to_string(n) + " read)");
          expect_fields(3, "pt <u> <v>");
          const glm::dvec2 q{number(1, "u"), number(2, "v")};
          if (q.x < 0 || q.x > 1 || q.y < 0 || q.y > 1) fail("trim point lies outside the domain [0,1]²");
          pts.push_back(q);
        }
        if (!loop.segments.empty() &&
            glm::length(loop.segments.back().control.back() - pts.front()) > kClosureTolerance) {
          fail("segment does not start where the previous one ends");
        }
        if (curve) {
          loop.segments.push_back({std::move(pts)});
        } else {
          for (std::size_t k = 0; k + 1 < pts.size(); ++k) loop.segments.push_back({{pts[k], pts[k + 1]}});
        }
      } else {
        fail("unknown keyword '" + std::string(key) + "' in a loop (curve, polyline, endloop)");
      }
    }
    return loop;  // unreachable
  }

  // Orientation (outer CCW, holes CW) of each loop of a finished surface, then the loops together: no crossing
  // or touching, no retraced edge, holes inside the outer loop and not inside each other (loop_validation.hpp).
  void check_loops(const Surface& s) {
    const std::size_t first = loop_lines_.size() - s.loops.size();
    std::vector<std::vector<glm::dvec2>> polygons;
    for (std::size_t k = 0; k < s.loops.size(); ++k) {
      const int at = loop_lines_[first + k];
      polygons.push_back(sample_loop(s.loops[k]));
      const double area2 = signed_area2(polygons.back());
      if (std::abs(area2) < 1e-14) throw ModelError(file_, at, "loop encloses no area");
      if (k == 0 && area2 < 0)
        throw ModelError(file_, at, "outer loop is clockwise (material must lie on its left: counter-clockwise)");
      if (k > 0 && area2 > 0) throw ModelError(file_, at, "hole loop is counter-clockwise (holes run clockwise)");
    }
    if (const std::optional<LoopDefect> d = find_loop_defect(polygons)) {
      const int at = loop_lines_[first + std::max(d->loop, d->other)];
      std::ostringstream why;
      why << describe(*d) << " near (" << d->near.x << ", " << d->near.y << "): the loop";
      if (d->other != d->loop) {
        why << "s at lines " << loop_lines_[first + std::min(d->loop, d->other)] << " and " << at;
      } else {
        why << " at line " << at;
      }
      throw ModelError(file_, at, why.str());
    }
  }

  static std::string format_limit(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  static constexpr std::size_t kMaxLineLength = 1 << 16;
  std::istream& in_;
  std::string file_;
  int line_ = 0;
  int component_line_ = 0;
  std::string line_text_;
  std::vector<std::string> words_;
  std::vector<int> loop_lines_;  // line of each parsed loop's 'loop' keyword, for later checks
};

}  // namespace

Model parse_model(std::istream& in, const std::string& file_name) { return Parser(in, file_name).parse(); }

Model load_model(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found)
    throw ModelError(path, 0, "cannot open the file: no such file");
  if (status.type() == std::filesystem::file_type::directory)
    throw ModelError(path, 0, "cannot open the file: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(path, 0, std::string("cannot open the file: ") + std::strerror(errno));
  return parse_model(in, path);
}

void write_model(std::ostream& out, const Model& model) {
  // Refuse to write a file the parser would refuse (an 'inf' written here used to fail only at the next load).
  for (const Surface& s : model.surfaces) {
    for (int i = 0; i <= s.patch.degree_u; ++i) {
      for (int j = 0; j <= s.patch.degree_v; ++j) {
        const glm::dvec3 p = s.patch.point(i, j);
        const double w = s.patch.weight(i, j);
        const bool ok = std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate &&
                        std::abs(p.z) <= kMaxCoordinate && w >= kMinWeight && w <= kMaxWeight;
        if (!ok) {
          throw std::invalid_argument("write_model: surface '" + s.name +
                                      "' has a control point or weight that is not finite or out of range");
        }
      }
    }
  }
  out << "frontsteal-model 1\n" << std::setprecision(17);
  if (!model.name.empty()) out << "model " << model.name << "\n";
  for (const Surface& s : model.surfaces) {
    out << "surface" << (s.name.empty() ? "" : " " + s.name) << "\n";
    if (s.component >= 0) out << "  component " << s.component << "\n";
    if (s.solid) out << "  solid\n";
    out << "  patch " << s.patch.degree_u << " " << s.patch.degree_v << "\n";
    for (int i = 0; i <= s.patch.degree_u; ++i) {
      for (int j = 0; j <= s.patch.degree_v; ++j) {
        const glm::dvec3 p = s.patch.point(i, j);
        out << "  cp " << p.x << " " << p.y << " " << p.z;
        if (s.patch.weight(i, j) != 1.0) out << " " << s.patch.weight(i, j);
        out << "\n";
      }
    }
    for (const TrimLoop& loop : s.loops) {
      out << "  loop\n";
      for (std::size_t k = 0; k < loop.segments.size();) {
        // Runs of straight segments are written as one polyline.
        std::size_t run = k;
        while (run < loop.segments.size() && loop.segments[run].degree() == 1) ++run;
        if (run > k) {
          out << "    polyline " << run - k + 1 << "\n";
          for (std::size_t q = k; q < run; ++q)
            out << "    pt " << loop.segments[q].control[0].x << " " << loop.segments[q].control[0].y << "\n";
          out << "    pt " << loop.segments[run - 1].control[1].x << " " << loop.segments[run - 1].control[1].y << "\n";
          k = run;
          continue;
        }
        const TrimSegment& seg = loop.segments[k++];
        out << "    curve " << seg.degree() << "\n";
        for (const glm::dvec2& q : seg.control) out << "    pt " << q.x << " " << q.y << "\n";
      }
      out << "  endloop\n";
    }
    out << "endsurface\n";
  }
}

}  // namespace frontsteal::tess
