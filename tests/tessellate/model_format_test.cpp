// The native model format (tessellate/model_format.hpp): a valid trimmed model parses and round-trips; every
// kind of bad input is rejected with file:line and the reason, and nothing is half-loaded.
#include "tessellate/model_format.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>

namespace ts = frontsteal::tess;

namespace {

// A bilinear plate with a square hole: outer loop CCW (polyline), hole CW (two straight 'curve' segments and
// a quadratic one).
const char* const kPlate = R"(# a plate with a hole
frontsteal-model 1
model plate
surface plate_top
  component 0
  patch 1 1
  cp 0 0 0
  cp 0 1 0
  cp 1 0 0
  cp 1 1 0 2.0
  loop
    polyline 5
    pt 0 0
    pt 1 0
    pt 1 1
    pt 0 1
    pt 0 0
  endloop
  loop
    curve 1
    pt 0.4 0.4
    pt 0.4 0.6
    curve 1
    pt 0.4 0.6
    pt 0.6 0.6
    curve 2
    pt 0.6 0.6
    pt 0.7 0.5
    pt 0.4 0.4
  endloop
endsurface
)";

ts::Model parse(const std::string& text) {
  std::istringstream in(text);
  return ts::parse_model(in, "plate.fsm");
}

// The text of kPlate with line `line` (1-based) replaced.
std::string with_line(int line, const std::string& replacement) {
  std::istringstream in(kPlate);
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) out += (n == line ? replacement : l) + "\n";
  return out;
}

}  // namespace

TEST_CASE("a trimmed plate parses", "[tessellate][format]") {
  const ts::Model m = parse(kPlate);
  REQUIRE(m.surfaces.size() == 1);
  const ts::Surface& s = m.surfaces[0];
  CHECK(m.name == "plate");
  CHECK(s.name == "plate_top");
  CHECK(s.component == 0);
  CHECK(s.patch.degree_u == 1);
  CHECK(s.patch.weight(1, 1) == 2.0);
  CHECK(s.patch.point(1, 1) == glm::dvec3(1, 1, 0));
  REQUIRE(s.loops.size() == 2);
  CHECK(s.loops[0].segments.size() == 4);  // polyline of 5 points
  CHECK(s.loops[1].segments.size() == 3);
  CHECK(ts::signed_area2(ts::sample_loop(s.loops[0])) > 0);
  CHECK(ts::signed_area2(ts::sample_loop(s.loops[1])) < 0);
}

TEST_CASE("write then parse reproduces the model", "[tessellate][format]") {
  const ts::Model m = parse(kPlate);
  std::ostringstream out;
  ts::write_model(out, m);
  const ts::Model again = parse(out.str());
  REQUIRE(again.surfaces.size() == m.surfaces.size());
  const auto& a = m.surfaces[0];
  const auto& b = again.surfaces[0];
  for (int i = 0; i <= a.patch.degree_u; ++i) {
    for (int j = 0; j <= a.patch.degree_v; ++j) {
      CHECK(glm::length(a.patch.homogeneous(i, j) - b.patch.homogeneous(i, j)) < 1e-15);
    }
  }
  REQUIRE(b.loops.size() == a.loops.size());
  CHECK(ts::sample_loop(b.loops[1]) == ts::sample_loop(a.loops[1]));
}

TEST_CASE("bad input names file:line and the reason", "[tessellate][format]") {
  struct Case {
    std::string text;
    std::string expected;  // a substring of the message
  };
  const Case cases[] = {
      {"", "plate.fsm:0: expected the header"},
      {"frontsteal-model 2\n", "plate.fsm:1: expected the header"},
      {with_line(4, "surfaces plate_top"), "plate.fsm:4: unknown keyword 'surfaces'"},
      {with_line(6, "  patch 0 1"), "plate.fsm:6: degree 0 is out of range 1..25"},
      {with_line(6, "  patch 26 1"), "plate.fsm:6: degree 26 is out of range 1..25"},
      {with_line(7, "  cp 0 nan 0"), "plate.fsm:7: y 'nan' is not finite"},
      {with_line(7, "  cp 0 1e999 0"), "plate.fsm:7: y '1e999' is out of the range of a double"},
      {with_line(7, "  cp 0 zero 0"), "plate.fsm:7: y 'zero' is not a number"},
      {with_line(10, "  cp 1 1 0 0"), "plate.fsm:10: weight 0 must be > 0"},
      {with_line(10, "  cp 1 1 0 -2"), "plate.fsm:10: weight -2 must be > 0"},
      {with_line(10, "  cp 1 1"), "plate.fsm:10: expected 'cp <x> <y> <z> [<w>]'"},
      {with_line(10, "  # one control point short"), "control points"},
      {with_line(14, "    pt 1.5 0"), "plate.fsm:14: trim point lies outside the domain"},
      {with_line(17, "    pt 0 0.5"), "is not closed"},
      {with_line(24, "    pt 0.5 0.6"), "plate.fsm:25: segment does not start where the previous one ends"},
      {with_line(30, "  # endloop missing"), "plate.fsm:31: unknown keyword 'endsurface' in a loop"},
      {with_line(31, ""), "plate.fsm:31: the file ends inside a 'surface' block"},
      {with_line(12, "    polyline 1"), "plate.fsm:12: polyline count 1 is out of range 2..1048576"},
  };
  for (const Case& c : cases) {
    INFO("input:\n" << c.text);
    try {
      parse(c.text);
      FAIL("accepted bad input; expected: " << c.expected);
    } catch (const ts::ModelError& e) {
      CHECK_THAT(e.what(), Catch::Contains(c.expected));
    }
  }
}

TEST_CASE("loops of the wrong orientation or crossing themselves are rejected", "[tessellate][format]") {
  // Outer loop clockwise: reverse the polyline.
  std::string cw = kPlate;
  cw.replace(cw.find("pt 1 0\n    pt 1 1\n    pt 0 1"), std::string("pt 1 0\n    pt 1 1\n    pt 0 1").size(),
             "pt 0 1\n    pt 1 1\n    pt 1 0");
  CHECK_THROWS_WITH(parse(cw), Catch::Contains("plate.fsm:11: outer loop is clockwise"));
  // A bow tie: (0,0) (1,1) (1,0) (0,1) crosses itself.
  std::string bow = kPlate;
  bow.replace(bow.find("pt 1 0\n    pt 1 1\n    pt 0 1"), std::string("pt 1 0\n    pt 1 1\n    pt 0 1").size(),
              "pt 1 1\n    pt 1 0\n    pt 0 1");
  CHECK_THROWS_WITH(parse(bow), Catch::Contains("plate.fsm:11:"));
  // A hole running counter-clockwise.
  const ts::Model ok = parse(kPlate);
  std::ostringstream out;
  ts::Model flipped = ok;
  auto& hole = flipped.surfaces[0].loops[1];
  std::reverse(hole.segments.begin(), hole.segments.end());
  for (auto& seg : hole.segments) std::reverse(seg.control.begin(), seg.control.end());
  ts::write_model(out, flipped);
  CHECK_THROWS_WITH(parse(out.str()), Catch::Contains("hole loop is counter-clockwise"));
}

TEST_CASE("holes that cross, touch, nest or lie outside are refused with both loops' lines", "[tessellate][format]") {
  // kPlate's hole is the loop at line 19; a second hole is appended after it (its 'loop' on line 31).
  const auto with_second_hole = [](const std::string& points) {
    std::string text = kPlate;
    text.replace(text.find("endsurface"), std::string("endsurface").size(),
                 "  loop\n    polyline 5\n" + points + "  endloop\nendsurface");
    return text;
  };
  const auto pts = [](std::initializer_list<std::pair<double, double>> list) {
    std::ostringstream s;
    for (const auto& [u, v] : list) s << "    pt " << u << " " << v << "\n";
    return s.str();
  };
  // Crosses the first hole (the square 0.4..0.6 with a bulge to 0.7).
  CHECK_THROWS_WITH(
      parse(with_second_hole(pts({{0.5, 0.5}, {0.5, 0.8}, {0.8, 0.8}, {0.8, 0.5}, {0.5, 0.5}}))),
      Catch::Contains("plate.fsm:31: loops cross or touch each other") && Catch::Contains("lines 19 and 31"));
  // Inside the first hole.
  CHECK_THROWS_WITH(parse(with_second_hole(pts({{0.45, 0.45}, {0.45, 0.5}, {0.5, 0.5}, {0.5, 0.45}, {0.45, 0.45}}))),
                    Catch::Contains("plate.fsm:31: hole lies inside another hole"));
  // Touching the outer loop along the bottom edge.
  CHECK_THROWS_WITH(parse(with_second_hole(pts({{0.1, 0.0}, {0.1, 0.2}, {0.2, 0.2}, {0.2, 0.0}, {0.1, 0.0}}))),
                    Catch::Contains("plate.fsm:31: loops cross or touch each other"));
  // Apart from everything: accepted.
  CHECK(parse(with_second_hole(pts({{0.1, 0.1}, {0.1, 0.2}, {0.2, 0.2}, {0.2, 0.1}, {0.1, 0.1}})))
            .surfaces[0]
            .loops.size() == 3);
}

TEST_CASE("a missing file is a clear error", "[tessellate][format]") {
  CHECK_THROWS_WITH(ts::load_model("no/such/model.fsm"), Catch::Contains("no/such/model.fsm:0: cannot open the file"));
}
