// Tests for reporting/results_dir.hpp: gnuplot_text, the one escaping every plot title goes through, and
// write_gnuplot, the one opening every plot script shares.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "reporting/results_dir.hpp"

namespace report = frontsteal::report;

TEST_CASE("gnuplot_text escapes quotes and backslashes and drops control characters", "[results_dir]") {
  CHECK(report::gnuplot_text("a \"b\" c\\d\te\n") == "a \\\"b\\\" c\\\\de");
  CHECK(report::gnuplot_text("x; y") == "x; y");  // no break unless asked
}

TEST_CASE("gnuplot_text breaks a long title after each semicolon and space when asked", "[results_dir]") {
  CHECK(report::gnuplot_text("2 ranks; owner calls; osc", true) == "2 ranks;\\nowner calls;\\nosc");
  CHECK(report::gnuplot_text("a;b;", true) == "a;b;");  // only "; " breaks
}

TEST_CASE("every gnuplot script opens the same way and draws a PNG of the asked size", "[results_dir]") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("frontsteal-results-dir-test-" + std::to_string(::getpid()));
  const report::ResultsDir results("frontsteal-test", dir);
  results.write_gnuplot("plot.gp", {320, 200, ""}, "set output 'plot.png'\nplot x\n");
  std::ifstream script(dir / "plot.gp");
  const std::string text{std::istreambuf_iterator<char>(script), {}};
  CHECK(text == "# gnuplot script written by frontsteal-test; run from " + dir.string() +
                    ": gnuplot plot.gp\nset terminal pngcairo size 320,200\nset output 'plot.png'\nplot x\n");
  results.write_gnuplot("fonts.gp", {}, "");
  std::ifstream fonts(dir / "fonts.gp");
  std::string first, second;
  std::getline(fonts, first);
  std::getline(fonts, second);
  CHECK(second == "set terminal pngcairo size 1100,640 font 'sans,10'");
  // The image itself, read as bytes, not through gnuplot: the PNG signature and the IHDR width and height.
  REQUIRE(results.plot("plot.gp"));
  std::ifstream png(dir / "plot.png", std::ios::binary);
  unsigned char head[24] = {};
  png.read(reinterpret_cast<char*>(head), sizeof head);
  REQUIRE(png.gcount() == 24);
  CHECK(head[0] == 0x89);
  CHECK(std::string(reinterpret_cast<char*>(head) + 1, 3) == "PNG");
  const auto be32 = [&](int at) {
    return (head[at] << 24) | (head[at + 1] << 16) | (head[at + 2] << 8) | head[at + 3];
  };
  CHECK(be32(16) == 320);
  CHECK(be32(20) == 200);
  std::filesystem::remove_all(dir);
}
