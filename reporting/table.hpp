// table.hpp — one table, four renderings: aligned text for the terminal, GitHub markdown, CSV and JSON.
//
// Every frontsteal executable reports through this type, so a column is named once and the four files it
// appears in cannot drift apart (they did: each main wrote its markdown, CSV and JSON by hand, with three
// spellings of a column). A cell keeps two faces: the text shown in the terminal and the markdown (rounded
// for reading), and the value written to CSV and JSON (full precision, a number where it is one).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "reporting/json.hpp"

namespace frontsteal::report {

struct Cell {
  std::string text;  // as shown (terminal, markdown)
  Json value;        // as stored (CSV, JSON): a number, a string, a bool or null

  Cell() = default;
  Cell(std::string s) : text(s), value(std::move(s)) {}                // NOLINT: implicit on purpose
  Cell(const char* s) : Cell(std::string(s)) {}                        // NOLINT
  Cell(std::string_view s) : Cell(std::string(s)) {}                   // NOLINT
  Cell(std::int64_t v) : text(std::to_string(v)), value(v) {}          // NOLINT
  Cell(std::uint64_t v) : text(std::to_string(v)), value(v) {}         // NOLINT
  Cell(int v) : Cell(static_cast<std::int64_t>(v)) {}                  // NOLINT
  Cell(unsigned v) : Cell(static_cast<std::uint64_t>(v)) {}            // NOLINT
  Cell(long long v) : Cell(static_cast<std::int64_t>(v)) {}            // NOLINT
  Cell(unsigned long long v) : Cell(static_cast<std::uint64_t>(v)) {}  // NOLINT
  Cell(bool v) : text(v ? "yes" : "no"), value(v) {}                   // NOLINT

  // A measured or computed real: shown with `digits` decimals, stored exactly.
  static Cell fixed(double v, int digits);
  // A value shown one way and stored another (e.g. "12 (not met)" stored as 12).
  static Cell shown_as(std::string text, Json value);
  // Nothing to report (an empty cell; null in JSON).
  static Cell empty() { return shown_as("", nullptr); }
};

struct Column {
  std::string key;      // CSV header and JSON key: lower_snake_case
  std::string header;   // terminal and markdown header: words, with the unit
  bool numeric = true;  // right-aligned (markdown ---:) when true
};

class Table {
 public:
  explicit Table(std::vector<Column> columns);

  // Appends a row; it must have one cell per column.
  void add_row(std::vector<Cell> cells);
  std::size_t rows() const noexcept { return rows_.size(); }
  const std::vector<Column>& columns() const noexcept { return columns_; }
  const Cell& at(std::size_t row, std::size_t column) const { return rows_.at(row).at(column); }

  std::string markdown() const;  // | header | ... | with ---: under numeric columns
  std::string terminal() const;  // columns padded to their widest cell, two spaces apart
  std::string csv() const;       // keys, then values (strings quoted when they need it)
  Json json() const;             // an array of objects, one per row, keyed by column key

 private:
  std::vector<Column> columns_;
  std::vector<std::vector<Cell>> rows_;
};

// "12.3" for fixed(12.345, 1): the text the terminal and markdown show.
std::string fixed_text(double v, int digits);

}  // namespace frontsteal::report
