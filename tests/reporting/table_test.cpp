// Tests for reporting/table.hpp: the four renderings of one table, written out by hand here.
#include <catch2/catch.hpp>

#include <stdexcept>

#include "reporting/table.hpp"

namespace report = frontsteal::report;

namespace {

report::Table sample() {
  report::Table t({{"scheduler", "scheduler", false}, {"frames", "frames"}, {"ms", "ms per frame"}});
  t.add_row({"queue-mutex", 24, report::Cell::fixed(12.3456, 1)});
  t.add_row({"a, \"quoted\" name", std::uint64_t{7}, report::Cell::empty()});
  return t;
}

}  // namespace

TEST_CASE("a table renders as markdown with right-aligned numeric columns", "[reporting]") {
  CHECK(sample().markdown() ==
        "| scheduler | frames | ms per frame |\n"
        "|---|---:|---:|\n"
        "| queue-mutex | 24 | 12.3 |\n"
        "| a, \"quoted\" name | 7 |  |\n");
}

TEST_CASE("CSV keeps full precision and quotes what needs quoting", "[reporting]") {
  CHECK(sample().csv() ==
        "scheduler,frames,ms\n"
        "queue-mutex,24,12.3456\n"
        "\"a, \"\"quoted\"\" name\",7,\n");
}

TEST_CASE("JSON rows are objects keyed by column, numbers as numbers, empty as null", "[reporting]") {
  const report::Json j = sample().json();
  REQUIRE(j.size() == 2);
  CHECK(j[0]["scheduler"] == "queue-mutex");
  CHECK(j[0]["frames"] == 24);
  CHECK(j[0]["ms"].get<double>() == 12.3456);
  CHECK(j[1]["ms"].is_null());
  CHECK(j[0].dump() == R"({"scheduler":"queue-mutex","frames":24,"ms":12.3456})");  // column order kept
}

TEST_CASE("the terminal rendering pads every column to its widest cell", "[reporting]") {
  report::Table t({{"name", "name", false}, {"n", "n"}});
  t.add_row({"a", 100});
  t.add_row({"bbbb", 2});
  CHECK(t.terminal() ==
        "name    n\n"
        "a     100\n"
        "bbbb    2\n");
}

TEST_CASE("a row with the wrong number of cells is refused", "[reporting]") {
  report::Table t({{"a", "a"}, {"b", "b"}});
  CHECK_THROWS_AS(t.add_row({1}), std::logic_error);
  CHECK(t.rows() == 0);
}
