// import_main.cpp — frontsteal-import: STEP / IGES / BREP files into one native model file (.fsm).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/cli_args.hpp"
#include "tessellate/isolated_import.hpp"
#include "tessellate/model_format.hpp"
#include "tessellate/occt_import.hpp"

namespace {

namespace tess = frontsteal::tess;
namespace fsys = std::filesystem;

constexpr std::string_view kProgram = "frontsteal-import";
constexpr std::string_view kUsage = R"(frontsteal-import — CAD files (STEP, IGES, BREP) into a frontsteal model, through Open CASCADE.

Usage: frontsteal-import IN [IN...] -o OUT.fsm [--report REPORT.json] [--samples N] [--time-limit S]
                         [--memory-limit MB]

  IN                  .step/.stp, .iges/.igs or .brep files (chosen by extension, any case)
  -o, --output FILE   the model to write (native format: tessellate/model_format.hpp)
  --report FILE       also write the per-file reports as JSON
  --samples N         trim-curve samples per knot span of a p-curve (default 8, 1..1000)
  --time-limit S      seconds one file's reader may run (default 30)
  --memory-limit MB   resident memory one file's reader may use, MiB (default 4096)
  -h, --help          this text

Every face is converted to B-splines (BRepBuilderAPI_NurbsConvert), split at its knots into rational Bézier
patches (degree <= 7 each way; higher-degree faces are skipped), and its trim loops (the wires' p-curves,
sampled to polylines) are cut along the patch grid, so each patch gets its own loops in [0,1]². Every surface
written passes the native format's strict checks. Progress goes to stderr; the per-file report (faces,
imported faces, Bézier patches, surfaces, trim loops, loops reversed to fit their nesting ("reorient"),
loops with a tiny corner loop cut off ("corners"), and what was skipped, grouped by reason) to stdout.
Each file is read in a child process under the time and memory limits (Open CASCADE's readers can crash or
run forever on hostile files): a reader that crashes, runs out of time or memory, or fails is reported with
the file and the cause, and nothing is written. A file that looks cut short (no STEP trailer, no IGES
terminate section) is imported with a warning.
Exit status: 0 on success, 1 when an input cannot be read or the output cannot be written, 2 for bad usage.
)";

struct Options {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  int samples = 8;
  tess::IsolationLimits limits;
};

[[noreturn]] void usage_error(const std::string& message) { frontsteal::cli::usage_error(kProgram, message); }

Options parse(int argc, char** argv) {
  Options o;
  frontsteal::cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view arg = args.flag();
    if (arg == "-o" || arg == "--output") {
      if (!o.output.empty()) usage_error("the output is given twice");
      o.output = args.value();
      if (o.output.empty()) usage_error(std::string(arg) + " needs a file name");
    } else if (arg == "--report") {
      o.report = args.value();
      if (o.report.empty()) usage_error("--report needs a file name");
    } else if (arg == "--samples") {
      o.samples = frontsteal::cli::parse_number<int>(kProgram, arg, args.value(), 1, 1000);
    } else if (arg == "--time-limit") {
      o.limits.time_limit_s = frontsteal::cli::parse_number<double>(kProgram, arg, args.value(), 0.1, 86400.0);
    } else if (arg == "--memory-limit") {
      o.limits.memory_limit_mb = frontsteal::cli::parse_number<double>(kProgram, arg, args.value(), 16.0, 1e7);
    } else if (arg.size() > 1 && arg[0] == '-') {
      usage_error("unknown option '" + std::string(arg) + "'");
    } else {
      o.inputs.emplace_back(arg);
    }
  }
  if (o.inputs.empty()) usage_error("no input file (give one or more .step/.stp/.iges/.igs/.brep files)");
  if (o.output.empty()) usage_error("no output file (-o OUT.fsm)");
  return o;
}

std::string json_string(std::string_view s) {
  std::ostringstream o;
  o << '"';
  for (const char c : s) {
    switch (c) {
      case '"': o << "\\\""; break;
      case '\\': o << "\\\\"; break;
      case '\n': o << "\\n"; break;
      case '\t': o << "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          o << "\\u" << std::hex << std::setw(4) << std::setfill('0') << static_cast<int>(c) << std::dec;
        } else {
          o << c;
        }
    }
  }
  o << '"';
  return o.str();
}

// Skips grouped by reason, most frequent first.
std::vector<std::pair<std::string, int>> by_reason(const tess::ImportReport& r) {
  std::map<std::string, int> counts;
  for (const tess::ImportSkip& s : r.skipped) ++counts[s.reason];
  std::vector<std::pair<std::string, int>> out(counts.begin(), counts.end());
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

struct FileResult {
  tess::ImportReport report;
  double seconds = 0;
};

void print_table(const std::vector<FileResult>& results) {
  std::size_t w = 4;
  for (const FileResult& f : results) w = std::max(w, fsys::path(f.report.file).filename().string().size());
  std::cout << std::left << std::setw(static_cast<int>(w)) << "file" << std::right << std::setw(8) << "faces"
            << std::setw(10) << "imported" << std::setw(9) << "patches" << std::setw(10) << "surfaces" << std::setw(8)
            << "loops" << std::setw(10) << "reorient" << std::setw(9) << "corners" << std::setw(9) << "skipped" << std::setw(9) << "seconds" << "\n";
  for (const FileResult& f : results) {
    const tess::ImportReport& r = f.report;
    std::cout << std::left << std::setw(static_cast<int>(w)) << fsys::path(r.file).filename().string() << std::right
              << std::setw(8) << r.faces << std::setw(10) << r.faces_imported << std::setw(9) << r.patches
              << std::setw(10) << r.surfaces << std::setw(8) << r.trim_loops << std::setw(10) << r.loops_reoriented
              << std::setw(9) << r.corner_loops_cut << std::setw(9) << r.skipped.size() << std::setw(9) << std::fixed << std::setprecision(2) << f.seconds
              << "\n";
  }
  for (const FileResult& f : results) {
    const auto groups = by_reason(f.report);
    if (groups.empty()) continue;
    std::cout << "skipped in " << fsys::path(f.report.file).filename().string() << ":\n";
    for (const auto& [reason, count] : groups) std::cout << "  " << std::setw(6) << count << "  " << reason << "\n";
  }
}

void write_report_json(std::ostream& o, const Options& opt, const std::vector<FileResult>& results, std::size_t surfaces) {
  o << "{\n  \"output\": " << json_string(opt.output) << ",\n  \"samples_per_span\": " << opt.samples
    << ",\n  \"surfaces\": " << surfaces << ",\n  \"files\": [";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const tess::ImportReport& r = results[i].report;
    o << (i ? "," : "") << "\n    {\"file\": " << json_string(r.file) << ", \"faces\": " << r.faces
      << ", \"faces_imported\": " << r.faces_imported << ", \"patches\": " << r.patches << ", \"surfaces\": " << r.surfaces
      << ", \"trim_loops\": " << r.trim_loops << ", \"loops_reoriented\": " << r.loops_reoriented
      << ", \"corner_loops_cut\": " << r.corner_loops_cut << ", \"warnings\": [";
    for (std::size_t k = 0; k < r.warnings.size(); ++k) o << (k ? ", " : "") << json_string(r.warnings[k]);
    o << "]"
      << ", \"seconds\": " << std::fixed << std::setprecision(3) << results[i].seconds << ",\n     \"skipped_by_reason\": [";
    const auto groups = by_reason(r);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      o << (g ? ", " : "") << "{\"reason\": " << json_string(groups[g].first) << ", \"count\": " << groups[g].second << "}";
    }
    o << "],\n     \"skipped\": [";
    for (std::size_t s = 0; s < r.skipped.size(); ++s) {
      o << (s ? ", " : "") << "{\"face\": " << r.skipped[s].face << ", \"reason\": " << json_string(r.skipped[s].reason) << "}";
    }
    o << "]}";
  }
  o << "\n  ]\n}\n";
}

// Writes through a temporary file and renames, so a failed run leaves no half-written output.
bool write_file(const std::string& path, const std::string& what, const auto& write) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) {
      std::cerr << kProgram << ": error: cannot write the " << what << " '" << path << "'\n";
      return false;
    }
    write(out);
    out.flush();
    if (!out) {
      std::cerr << kProgram << ": error: writing the " << what << " '" << path << "' failed\n";
      std::remove(tmp.c_str());
      return false;
    }
  }
  std::error_code ec;
  fsys::rename(tmp, path, ec);
  if (ec) {
    std::cerr << kProgram << ": error: cannot move " << tmp << " to " << path << ": " << ec.message() << "\n";
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  // Fail before the (slow) import when the output's folder is missing.
  for (const std::string& out : {opt.output, opt.report}) {
    if (out.empty()) continue;
    const fsys::path dir = fsys::path(out).parent_path();
    if (!dir.empty() && !fsys::is_directory(dir)) {
      std::cerr << kProgram << ": error: the folder of '" << out << "' does not exist\n";
      return 1;
    }
  }

  tess::Model model;
  model.name = fsys::path(opt.output).stem().string();
  for (char& c : model.name) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == '#') c = '_';
  }
  const tess::ImportOptions import_options{.samples_per_span = opt.samples};
  std::vector<FileResult> results;
  for (const std::string& in : opt.inputs) {
    std::cerr << kProgram << ": reading " << in << " ...\n";
    const auto t0 = std::chrono::steady_clock::now();
    FileResult f;
    try {
      f.report = tess::import_cad_file_isolated(in, model, import_options, opt.limits);
    } catch (const std::exception& e) {
      std::cerr << kProgram << ": error: " << e.what() << "\n";
      return 1;
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cerr << kProgram << ": " << in << ": " << f.report.faces << " faces, " << f.report.faces_imported
              << " imported, " << f.report.surfaces << " surfaces, " << f.report.skipped.size() << " skipped, "
              << std::fixed << std::setprecision(2) << f.seconds << " s\n";
    for (const std::string& w : f.report.warnings) std::cerr << kProgram << ": warning: " << in << ": " << w << "\n";
    results.push_back(std::move(f));
  }

  print_table(results);
  if (!write_file(opt.output, "model", [&](std::ostream& o) { tess::write_model(o, model); })) return 1;
  std::cerr << kProgram << ": wrote " << model.surfaces.size() << " surfaces to " << opt.output << "\n";
  if (!opt.report.empty()) {
    if (!write_file(opt.report, "report", [&](std::ostream& o) { write_report_json(o, opt, results, model.surfaces.size()); })) {
      return 1;
    }
    std::cerr << kProgram << ": wrote the report to " << opt.report << "\n";
  }
  return 0;
}
