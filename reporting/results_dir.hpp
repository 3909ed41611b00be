// results_dir.hpp — where an executable's results go: one directory, files written whole, a JSON document
// with the common header, and gnuplot run on the scripts the program wrote.
//
// Why one type: every main created its directory, opened files, wrote JSON headers and called gnuplot in its
// own way, and reported failures (or not) in its own words. Here a file that cannot be written is an error
// that names the file (exit status 1 from the caller), never a silently missing result; a missing gnuplot is
// a warning (the .gp script and its data stay, to be plotted later).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "reporting/json.hpp"

namespace frontsteal::report {

// `s` as the body of a gnuplot double-quoted string: quotes and backslashes escaped, control characters
// dropped; with break_after_semicolons, "; " becomes a line break, so a long title wraps inside the image.
std::string gnuplot_text(std::string_view s, bool break_after_semicolons = false);

// The common header of every results file: {schema_version, program, kind, commit}.
Json document(std::string_view program, int schema_version, std::string_view kind, std::string_view commit);

// Reads a results file back; throws std::runtime_error naming the file when it cannot be read ("cannot read
// <what> '<path>'") or is not JSON ("<path>: not JSON: ...").
Json read_document(const std::filesystem::path& path, std::string_view what);

// Writes `text` to `path` through a temporary file renamed into place, so a failed run leaves no half-written
// file; throws std::runtime_error naming the file when it cannot.
void write_atomically(const std::filesystem::path& path, std::string_view text);

class ResultsDir {
 public:
  // Creates `dir` (and its parents); throws std::runtime_error naming it when that fails.
  ResultsDir(std::string program, std::filesystem::path dir);

  const std::filesystem::path& path() const noexcept { return dir_; }
  std::filesystem::path file(std::string_view name) const { return dir_ / name; }

  // Writes the whole file; throws std::runtime_error naming it when it cannot be written.
  void write(std::string_view name, std::string_view text) const;
  // Writes `doc` indented by 2, with a final newline.
  void write_json(std::string_view name, const Json& doc) const;
  // Runs gnuplot on `script` (a file already written in this directory) from inside the directory.
  // False, with a warning on stderr, when gnuplot is missing or fails; the script stays.
  bool plot(std::string_view script) const;
  // Writes the gnuplot script `name`: the opening every frontsteal script shares (which program wrote it and
  // how to re-plot it, the PNG terminal at `canvas`), then `commands` (set output, titles, plots). Throws as
  // write(); plot(name) then draws it.
  struct PngCanvas {
    int width = 1100, height = 640;
    std::string_view options = "font 'sans,10'";  // more pngcairo terminal options
  };
  void write_gnuplot(std::string_view name, PngCanvas canvas, std::string_view commands) const;

 private:
  std::string program_;
  std::filesystem::path dir_;
};

}  // namespace frontsteal::report
