// Hostile native model files (tests/tessellate/hostile/native/, listed with the expected error in
// expected.tsv): every one must be refused with a ModelError naming file:line and the real reason — no crash,
// no hang, no other exception, nothing half-loaded. Built and run in the release fast tier and again under
// ASan + UBSan (`cmake --workflow --preset hostile`, part of the README's test command).
#include <catch2/catch.hpp>

#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tessellate/model_format.hpp"
#include <unistd.h>

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;

namespace {

struct Case {
  std::string file;
  int line;
  std::string says;
};

const fsys::path kCorpus = fsys::path(FRONTSTEAL_TESTS_DIR) / "tessellate" / "hostile" / "native";

std::vector<Case> corpus() {
  std::vector<Case> cases;
  std::ifstream index(kCorpus / "expected.tsv");
  for (std::string row; std::getline(index, row);) {
    if (row.empty() || row[0] == '#') continue;
    const auto a = row.find('\t'), b = row.find('\t', a + 1);
    cases.push_back({row.substr(0, a), std::stoi(row.substr(a + 1, b - a - 1)), row.substr(b + 1)});
  }
  return cases;
}

}  // namespace

TEST_CASE("every hostile native file is refused with file:line and its real reason", "[hostile]") {
  const std::vector<Case> cases = corpus();
  REQUIRE(cases.size() >= 20);
  std::size_t files = 0;
  for (const auto& entry : fsys::directory_iterator(kCorpus)) files += entry.path().extension() == ".fsm";
  CHECK(files == cases.size());  // every corpus file has its expectation
  for (const Case& c : cases) {
    const std::string path = (kCorpus / c.file).string();
    INFO(c.file << ": expected line " << c.line << ", '" << c.says << "'");
    try {
      const ts::Model m = ts::load_model(path);
      FAIL("accepted, with " << m.surfaces.size() << " surfaces");
    } catch (const ts::ModelError& e) {
      INFO("got: " << e.what());
      CHECK(e.line() == c.line);
      CHECK(std::string(e.what()).find(c.says) != std::string::npos);
      CHECK(std::string(e.what()).starts_with(path + ":"));
    }
  }
}

TEST_CASE("negative control: the corpus's valid twin loads, so the refusals are about the defects", "[hostile]") {
  // kCorpus/../valid.fsm is the file every hostile case was made from, unchanged.
  const ts::Model m = ts::load_model((kCorpus.parent_path() / "valid.fsm").string());
  CHECK(m.surfaces.size() == 1);
}

TEST_CASE("a directory named like a model is not 'no such file'", "[hostile]") {
  const fsys::path dir = fsys::temp_directory_path() / ("frontsteal-hostile-" + std::to_string(::getpid())) / "x.fsm";
  fsys::create_directories(dir);
  CHECK_THROWS_WITH(ts::load_model(dir.string()), Catch::Contains("it is a directory"));
  CHECK_THROWS_WITH(ts::load_model((dir.parent_path() / "missing.fsm").string()), Catch::Contains("no such file"));
  fsys::remove_all(dir.parent_path());
}

TEST_CASE("the writer refuses numbers the parser would refuse, and writes nothing", "[hostile]") {
  ts::Model m = ts::load_model((kCorpus.parent_path() / "valid.fsm").string());
  m.surfaces[0].patch.set(1, 1, {1.0, 1.0, std::numeric_limits<double>::infinity()});
  std::ostringstream out;
  CHECK_THROWS_AS(ts::write_model(out, m), std::invalid_argument);
  CHECK(out.str().empty());
  m.surfaces[0].patch.set(1, 1, {1e155, 1.0, 0.0});
  CHECK_THROWS_AS(ts::write_model(out, m), std::invalid_argument);
}
