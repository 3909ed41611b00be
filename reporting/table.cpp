// table.cpp — the four renderings of report::Table.
#include "reporting/table.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace frontsteal::report {

std::string fixed_text(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

Cell Cell::fixed(double v, int digits) { return shown_as(fixed_text(v, digits), v); }

Cell Cell::shown_as(std::string text, Json value) {
  Cell c;
  c.text = std::move(text);
  c.value = std::move(value);
  return c;
}

Table::Table(std::vector<Column> columns) : columns_(std::move(columns)) {}

void Table::add_row(std::vector<Cell> cells) {
  if (cells.size() != columns_.size()) {
    throw std::logic_error("report::Table: a row of " + std::to_string(cells.size()) + " cells for " +
                           std::to_string(columns_.size()) + " columns");
  }
  rows_.push_back(std::move(cells));
}

std::string Table::markdown() const {
  std::ostringstream out;
  out << '|';
  for (const Column& c : columns_) out << ' ' << c.header << " |";
  out << "\n|";
  for (const Column& c : columns_) out << (c.numeric ? "---:|" : "---|");
  out << '\n';
  for (const auto& row : rows_) {
    out << '|';
    for (const Cell& cell : row) out << ' ' << cell.text << " |";
    out << '\n';
  }
  return out.str();
}

std::string Table::terminal() const {
  std::vector<std::size_t> width(columns_.size());
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    width[c] = columns_[c].header.size();
    for (const auto& row : rows_) width[c] = std::max(width[c], row[c].text.size());
  }
  std::ostringstream out;
  auto put = [&](std::size_t c, const std::string& text) {
    const std::string pad(width[c] - std::min(width[c], text.size()), ' ');
    if (c > 0) out << "  ";
    if (columns_[c].numeric) {
      out << pad << text;
    } else {
      out << text << (c + 1 < columns_.size() ? pad : "");
    }
  };
  for (std::size_t c = 0; c < columns_.size(); ++c) put(c, columns_[c].header);
  out << '\n';
  for (const auto& row : rows_) {
    for (std::size_t c = 0; c < columns_.size(); ++c) put(c, row[c].text);
    out << '\n';
  }
  return out.str();
}

namespace {

// RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled.
std::string csv_field(const Json& v) {
  if (v.is_null()) return "";
  if (!v.is_string()) return v.dump();
  const std::string& s = v.get_ref<const std::string&>();
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char ch : s) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + '"';
}

}  // namespace

std::string Table::csv() const {
  std::ostringstream out;
  for (std::size_t c = 0; c < columns_.size(); ++c) out << (c ? "," : "") << columns_[c].key;
  out << '\n';
  for (const auto& row : rows_) {
    for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << csv_field(row[c].value);
    out << '\n';
  }
  return out.str();
}

Json Table::json() const {
  Json rows = Json::array();
  for (const auto& row : rows_) {
    Json object = Json::object();
    for (std::size_t c = 0; c < row.size(); ++c) object[columns_[c].key] = row[c].value;
    rows.push_back(std::move(object));
  }
  return rows;
}

}  // namespace frontsteal::report
