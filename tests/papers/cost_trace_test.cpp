// papers/cost_trace.hpp: the trace file the simulator replays, read from hostile text. Every malformed trace
// is refused with a TraceError that names the file and the line of the first problem, never read as a shorter
// or shifted trace; a well-formed one comes back exactly as written.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "papers/cost_trace.hpp"

namespace fp = frontsteal::papers;
namespace fs = std::filesystem;

namespace {

class TraceDir {
 public:
  TraceDir() : dir_(fs::temp_directory_path() / ("frontsteal-cost-trace-test-" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
  }
  ~TraceDir() { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  fs::path path(const std::string& name) const { return dir_ / name; }

 private:
  fs::path dir_;
};

const std::string kHeader = "frontsteal-cost-trace 1\nscene test\nsurfaces 2\nframes 2\n";
const std::string kSurfaces = "surface 0 0 0 0 1\nsurface 1 1 0 0 2\n";
const std::string kFrames = "frame 0 10 20\nframe 1 30 40\n";

}  // namespace

TEST_CASE("a well-formed trace reads back every number", "[papers][trace]") {
  const TraceDir dir;
  const fp::CostTrace t = fp::read_cost_trace(dir.write("ok.txt", kHeader + kSurfaces + kFrames));
  REQUIRE(t.surfaces() == 2);
  REQUIRE(t.frames() == 2);
  CHECK(t.scene == "test");
  CHECK(t.centres[1] == std::array<double, 3>{1, 0, 0});
  CHECK(t.estimates[1] == 2);
  CHECK(t.cost_ns[1][0] == 30);
  CHECK(t.frame_cost_ns(0) == 30);
  CHECK(t.path_cost_ns() == 100);

  fp::write_cost_trace(t, dir.path("again.txt"));
  const fp::CostTrace again = fp::read_cost_trace(dir.path("again.txt"));
  CHECK(again.cost_ns == t.cost_ns);
  CHECK(again.centres == t.centres);
}

TEST_CASE("a malformed trace is refused with the file and the line of its first problem", "[papers][trace]") {
  struct Case {
    const char* what;
    std::string text;
    std::string message;  // a part of the error's text
  };
  const Case cases[] = {
      {"empty", "", "empty file, not a frontsteal cost trace"},
      {"wrong magic", "frontsteal-cost-trace 2\n" + kSurfaces, ":1: not a frontsteal cost trace"},
      {"zero surfaces", "frontsteal-cost-trace 1\nsurfaces 0\n", ":2: bad surface count"},
      {"zero frames", "frontsteal-cost-trace 1\nsurfaces 2\nframes 0\n", ":3: bad frame count"},
      {"unknown key", kHeader + "colour blue\n", ":5: unknown key 'colour'"},
      {"surface out of order", kHeader + "surface 1 0 0 0 1\n", ":5: surface 1 out of order"},
      {"surface line short", kHeader + "surface 0 0 0\n", ":5: bad surface line"},
      {"frame out of order", kHeader + kSurfaces + "frame 1 10 20\n", ":7: frame out of order"},
      {"negative cost", kHeader + kSurfaces + "frame 0 10 -20\n", ":7: negative cost"},
      {"not a number", kHeader + kSurfaces + "frame 0 10 2x\n", ":7: bad cost value"},
      {"a cost missing", kHeader + kSurfaces + "frame 0 10\n", ":7: frame 0 has 1 costs, expected 2"},
      {"a cost too many", kHeader + kSurfaces + "frame 0 10 20 30\n", ":7: frame 0 has 3 costs, expected 2"},
      {"a surface missing", kHeader + "surface 0 0 0 0 1\n" + kFrames, "surface"},
      {"a frame missing", kHeader + kSurfaces + "frame 0 10 20\n", "frame lines, header says"},
  };
  const TraceDir dir;
  int i = 0;
  for (const Case& c : cases) {
    const fs::path file = dir.write("bad-" + std::to_string(++i) + ".txt", c.text);
    INFO(c.what);
    CHECK_THROWS_AS(fp::read_cost_trace(file), fp::TraceError);
    CHECK_THROWS_WITH(fp::read_cost_trace(file),
                      Catch::Contains(file.filename().string()) && Catch::Contains(c.message));
  }
}

TEST_CASE("a trace that cannot be opened or written says which file", "[papers][trace]") {
  CHECK_THROWS_WITH(fp::read_cost_trace("/nonexistent/trace.txt"),
                    Catch::Contains("cannot open trace /nonexistent/trace.txt"));
  fp::CostTrace t;
  t.centres = {{0, 0, 0}};
  t.estimates = {1};
  t.cost_ns = {{1}};
  CHECK_THROWS_WITH(fp::write_cost_trace(t, "/nonexistent/dir/trace.txt"),
                    Catch::Contains("/nonexistent/dir/trace.txt"));
}
