// results_dir.cpp — ResultsDir and the common JSON header.
#include "reporting/results_dir.hpp"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <system_error>

namespace frontsteal::report {

Json document(std::string_view program, int schema_version, std::string_view kind, std::string_view commit) {
  Json doc = Json::object();
  doc["schema_version"] = schema_version;
  doc["program"] = program;
  doc["kind"] = kind;
  doc["commit"] = commit;
  return doc;
}

std::string gnuplot_text(std::string_view s, bool break_after_semicolons) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (static_cast<unsigned char>(c) < 0x20) continue;
    if (break_after_semicolons && c == ';' && i + 1 < s.size() && s[i + 1] == ' ') {
      out += ";\\n";
      ++i;
      continue;
    }
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

Json read_document(const std::filesystem::path& path, std::string_view what) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + std::string(what) + " '" + path.string() + "'");
  try {
    return Json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": not JSON: " + e.what());
  }
}

void write_atomically(const std::filesystem::path& path, std::string_view text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path.string() + "'");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(tmp);
      throw std::runtime_error("writing '" + path.string() + "' failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw std::runtime_error("cannot move " + tmp.string() + " to " + path.string() + ": " + ec.message());
  }
}

ResultsDir::ResultsDir(std::string program, std::filesystem::path dir)
    : program_(std::move(program)), dir_(std::move(dir)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw std::runtime_error("cannot create " + dir_.string() + ": " + ec.message());
}

void ResultsDir::write(std::string_view name, std::string_view text) const {
  const std::filesystem::path p = file(name);
  std::ofstream out(p, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

void ResultsDir::write_json(std::string_view name, const Json& doc) const { write(name, doc.dump(2) + "\n"); }

void ResultsDir::write_gnuplot(std::string_view name, PngCanvas canvas, std::string_view commands) const {
  std::string text = "# gnuplot script written by " + program_ + "; run from " + dir_.string() + ": gnuplot " +
                     std::string(name) + "\nset terminal pngcairo size " + std::to_string(canvas.width) + "," +
                     std::to_string(canvas.height);
  if (!canvas.options.empty()) text += " " + std::string(canvas.options);
  text += "\n";
  text += commands;
  write(name, text);
}

bool ResultsDir::plot(std::string_view script) const {
  // Quoted for the shell: directory names with spaces or quotes must not break (or inject into) the command.
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string command = "cd " + quote(dir_.string()) + " && gnuplot " + quote(std::string(script));
  if (std::system(command.c_str()) == 0) return true;
  std::cerr << program_ << ": gnuplot failed or is missing (apt-get install gnuplot-nox); " << file(script).string()
            << " is written\n";
  return false;
}

}  // namespace frontsteal::report
