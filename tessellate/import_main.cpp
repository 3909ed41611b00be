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

#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "tessellate/isolated_import.hpp"
#include "tessellate/model_format.hpp"
#include "tessellate/occt_import.hpp"

namespace {

namespace tess = frontsteal::tess;
namespace fsys = std::filesystem;
namespace report = frontsteal::report;

constexpr const char* kProgram = "frontsteal-import";
constexpr const char* kDescription =
    "frontsteal-import — CAD files (STEP, IGES, BREP) into a frontsteal model, through Open CASCADE.";
constexpr const char* kFooter = R"(
Every face is converted to B-splines (BRepBuilderAPI_NurbsConvert), split at its knots into rational Bézier
patches at the face's own degree (any degree Open CASCADE allows, up to 25), and its trim loops (the wires' p-curves,
sampled to polylines) are cut along the patch grid, so each patch gets its own loops in [0,1]². Every surface
written passes the native format's strict checks. Progress goes to stderr; the per-file report (faces,
imported faces, Bézier patches, surfaces, trim loops, loops reversed to fit their nesting ("reorient"),
loops with a tiny corner loop cut off ("corners"), the largest distance of any patch from Open CASCADE's
own surface at 5x5 parameters per patch, in model units ("max error"), and what was skipped, grouped by
reason) to stdout.
Each file is read in a child process under the time and memory limits (Open CASCADE's readers can crash or
run forever on hostile files): a reader that crashes, runs out of time or memory, or fails is reported with
the file and the cause, and nothing is written. A file that looks cut short (no STEP trailer, no IGES
terminate section) is imported with a warning.
Exit status: 0 on success, 1 when an input cannot be read or the output cannot be written, 2 for bad usage.)";

struct Options {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  int samples = 8;
  tess::IsolationLimits limits;
};

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.app()
      .add_option("IN", o.inputs, ".step/.stp, .iges/.igs or .brep files (chosen by extension, any case)")
      ->required();
  cli.app()
      .add_option("-o,--output", o.output, "the model to write (native format: tessellate/model_format.hpp)")
      ->required()
      ->check(CLI::Validator([](std::string& f) { return f.empty() ? "needs a file name" : ""; }, ""));
  cli.option("--report", o.report, "also write the per-file reports as JSON")
      ->check(CLI::Validator([](std::string& f) { return f.empty() ? "needs a file name" : ""; }, ""));
  cli.option("--samples", o.samples, "trim-curve samples per knot span of a p-curve")->check(CLI::Range(1, 1000));
  cli.option("--time-limit", o.limits.time_limit_s, "seconds one file's reader may run")
      ->check(CLI::Range(0.1, 86400.0));
  cli.option("--memory-limit", o.limits.memory_limit_mb, "resident memory one file's reader may use, MiB")
      ->check(CLI::Range(16.0, 1e7));
  cli.parse(argc, argv);
  return o;
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

// The patches' largest distance from Open CASCADE's surface, in model units, in scientific notation (it
// spans 1e-16 to 1e-6 between files).
report::Cell error_cell(double error) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1e", error);
  return report::Cell::shown_as(text, error);
}

report::Table file_table(const std::vector<FileResult>& results) {
  report::Table t({{"file", "file", false},
                   {"faces", "faces"},
                   {"faces_imported", "imported"},
                   {"patches", "patches"},
                   {"surfaces", "surfaces"},
                   {"trim_loops", "loops"},
                   {"loops_reoriented", "reorient"},
                   {"corner_loops_cut", "corners"},
                   {"skipped_count", "skipped"},
                   {"max_patch_error", "max error"},
                   {"seconds", "seconds"}});
  for (const FileResult& f : results) {
    const tess::ImportReport& r = f.report;
    t.add_row({fsys::path(r.file).filename().string(), r.faces, r.faces_imported, r.patches, r.surfaces, r.trim_loops,
               r.loops_reoriented, r.corner_loops_cut, r.skipped.size(), error_cell(r.max_patch_error),
               report::Cell::fixed(f.seconds, 2)});
  }
  return t;
}

void print_report(const std::vector<FileResult>& results) {
  std::cout << file_table(results).terminal();
  for (const FileResult& f : results) {
    const auto groups = by_reason(f.report);
    if (groups.empty()) continue;
    std::cout << "skipped in " << fsys::path(f.report.file).filename().string() << ":\n";
    for (const auto& [reason, count] : groups) std::cout << "  " << std::setw(6) << count << "  " << reason << "\n";
  }
}

report::Json report_json(const Options& opt, const std::vector<FileResult>& results, std::size_t surfaces) {
  report::Json doc = report::document(kProgram, 1, "import", FRONTSTEAL_GIT_COMMIT);
  doc["output"] = opt.output;
  doc["samples_per_span"] = opt.samples;
  doc["surfaces"] = surfaces;
  report::Json files = report::Json::array();
  const report::Json rows = file_table(results).json();
  for (std::size_t i = 0; i < results.size(); ++i) {
    const tess::ImportReport& r = results[i].report;
    report::Json f = rows[i];
    f["file"] = r.file;  // the path as given, not only its name
    f["warnings"] = r.warnings;
    f["skipped_by_reason"] = report::Json::array();
    for (const auto& [reason, count] : by_reason(r))
      f["skipped_by_reason"].push_back({{"reason", reason}, {"count", count}});
    f["skipped"] = report::Json::array();
    for (const tess::ImportSkip& s : r.skipped) f["skipped"].push_back({{"face", s.face}, {"reason", s.reason}});
    files.push_back(std::move(f));
  }
  doc["files"] = std::move(files);
  return doc;
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

  print_report(results);
  try {
    std::ostringstream model_text;
    tess::write_model(model_text, model);
    report::write_atomically(opt.output, model_text.str());
    std::cerr << kProgram << ": wrote " << model.surfaces.size() << " surfaces to " << opt.output << "\n";
    if (!opt.report.empty()) {
      report::write_atomically(opt.report, report_json(opt, results, model.surfaces.size()).dump(2) + "\n");
      std::cerr << kProgram << ": wrote the report to " << opt.report << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
