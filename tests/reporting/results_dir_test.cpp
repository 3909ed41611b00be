// Tests for reporting/results_dir.hpp's gnuplot_text: the one escaping every plot title goes through.
#include <catch2/catch.hpp>

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
