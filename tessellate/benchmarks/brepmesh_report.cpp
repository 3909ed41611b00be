// brepmesh_report.cpp — brepmesh_comparison's table and files (brepmesh_report.hpp).
#include "tessellate/benchmarks/brepmesh_report.hpp"

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

#include "measure/machine_info.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/json.hpp"
#include "reporting/results_dir.hpp"

namespace frontsteal::brepmesh {

namespace {

namespace fsys = std::filesystem;

std::string fmt(double x, int digits = 3) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string timing(const Timing& t) { return fmt(t.median) + " [" + fmt(t.min) + ", " + fmt(t.max) + "]"; }

}  // namespace

void write_report(const Options& o, const std::vector<Row>& rows, const std::vector<std::string>& missing,
                  const std::string& load_before, const std::string& load_after) {
  // Stamp: machine, commit, date, load average.
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  const bool busy = std::atof(load_before.c_str()) > 1.0 || std::atof(load_after.c_str()) > 1.0;
  std::ostringstream stamp;
  stamp << "Measured " << date << " on " << frontsteal::cpu_model() << " (" << std::thread::hardware_concurrency()
        << " hardware threads), commit " << FRONTSTEAL_GIT_COMMIT << ", 1-minute load average " << load_before
        << " before and " << load_after << " after"
        << (busy ? " — the machine was busy (load > 1): times are inflated and noisy, ratios less so" : "")
        << ". Times are median [min, max] of " << o.repeats << " runs, in ms. BRepMesh: linear deflection ε absolute, "
        << "angular deflection " << o.angle << " rad, other parameters at their defaults; ours: steps from the "
        << "deviation bound at ε, size bound off, step cap " << o.max_steps << ", one thread.";

  std::ostringstream table;
  table << "| file | faces (compared) | ε / diagonal | ε | ours ms | BRepMesh 1T ms | BRepMesh par ms | "
           "BRepMesh 1T, compared faces only, ms | ours tri | BRepMesh tri (compared / all) | BRepMesh tri at 0.5 rad "
           "| ours max dev | ours mean dev | "
           "BRepMesh max dev | BRepMesh mean dev | time 1T ÷ ours | time par ÷ ours | tri BRepMesh ÷ ours |\n"
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : rows) {
    table << "| " << r.file << " | " << r.faces << " (" << r.faces_compared << ") | " << fmt(r.eps_fraction) << " | "
          << fmt(r.eps) << " | " << timing(r.ours) << " | " << timing(r.occt_serial) << " | " << timing(r.occt_parallel)
          << " | " << (r.timed_imported_only ? timing(r.occt_serial_imported) : std::string("= whole shape")) << " | "
          << r.our_triangles << " | " << r.occt_triangles << " / " << r.occt_triangles_all << " | "
          << r.occt_triangles_default_angle << " | " << fmt(r.our_dev.max) << " | " << fmt(r.our_dev.mean()) << " | "
          << fmt(r.occt_dev.max) << " | " << fmt(r.occt_dev.mean()) << " | "
          << fmt(r.occt_serial.median / r.ours.median) << " | " << fmt(r.occt_parallel.median / r.ours.median) << " | "
          << fmt(static_cast<double>(r.occt_triangles) / static_cast<double>(r.our_triangles)) << " |\n";
  }
  std::ostringstream notes;
  for (const Row& r : rows) {
    {
      notes << "- " << r.file << " at ε/diag " << fmt(r.eps_fraction) << ": largest edge tolerance "
            << fmt(r.edge_tolerance) << " (" << fmt(r.edge_tolerance / r.eps) << " ε); " << r.capped
            << " surfaces held at the step cap, " << r.inconsistencies << " audit inconsistencies, "
            << r.constrained_pieces << " pieces (of " << r.partial_cells
            << " partial cells) by the constrained triangulation, BRepMesh status flags " << r.occt_status
            << ", BRepMesh parallel triangles " << r.occt_triangles_parallel << " (1T: " << r.occt_triangles
            << "), largest distance at a vertex: ours " << fmt(r.our_dev.vertex_max) << ", BRepMesh "
            << fmt(r.occt_dev.vertex_max) << "\n";
    }
  }
  for (const std::string& m : missing) notes << "- missing, skipped: " << m << "\n";
  std::cout << stamp.str() << "\n\n" << table.str() << notes.str();

  const fsys::path dir(o.out);
  std::ofstream(dir / "brepmesh.md")
      << "# frontsteal vs Open CASCADE BRepMesh_IncrementalMesh on real CAD faces (measured)\n\n"
      << stamp.str() << "\n\n"
      << "Reproduce: `./build/release/tessellate/benchmarks/brepmesh_comparison --out results/tessellate`.\n\n"
      << "Deviation: distance from the triangle to the exact surface at the same (u, v), sampled at 12 barycentric "
         "points per triangle (the lattice of step 1/4 without the corners); max and mean over all samples, in model "
         "units. Both sides are measured on the faces frontsteal imported (\"compared\": faces that gave at least one "
         "surface; "
         "import_cad_file with its default 8 samples per p-curve span; pieces of a compared face that the importer "
         "rejected "
         "are missing on our side only); BRepMesh is timed on the whole shape, and on a compound of the compared faces "
         "alone where some faces were not imported. \"ours ms\" is "
         "planning + triangulation + the trimming audit of every imported surface; the import itself (once per file, "
         "like loading a model) is not included: it took "
      <<
      [&] {
        std::ostringstream s;
        for (std::size_t k = 0; k < rows.size(); k += o.eps_fractions.size()) {
          s << (k ? ", " : "") << rows[k].file << " " << fmt(rows[k].import_ms) << " ms";
        }
        return s.str();
      }()
      << ". The deviation measure sees the interior error only, not how closely the trimmed boundary follows the "
         "true edges.\n\n"
      << table.str() << "\nPer row (measured):\n\n"
      << notes.str();
  {
    std::ofstream csv(dir / "brepmesh.csv");
    csv << "file,faces,faces_compared,surfaces,trimmed,diagonal,eps_fraction,eps,import_ms,ours_ms_median,ours_ms_min,"
           "ours_ms_max,occt_1t_ms_median,occt_1t_ms_min,occt_1t_ms_max,occt_par_ms_median,occt_par_ms_min,occt_par_ms_"
           "max,"
           "occt_1t_compared_ms_median,ours_triangles,occt_triangles_compared,occt_triangles_all,"
           "occt_triangles_default_angle,ours_capped,"
           "ours_inconsistencies,ours_dev_max,ours_dev_mean,occt_dev_max,occt_dev_mean,occt_status\n";
    csv << std::setprecision(9);
    for (const Row& r : rows) {
      csv << r.file << ',' << r.faces << ',' << r.faces_compared << ',' << r.surfaces << ',' << r.trimmed << ','
          << r.diagonal << ',' << r.eps_fraction << ',' << r.eps << ',' << r.import_ms << ',' << r.ours.median << ','
          << r.ours.min << ',' << r.ours.max << ',' << r.occt_serial.median << ',' << r.occt_serial.min << ','
          << r.occt_serial.max << ',' << r.occt_parallel.median << ',' << r.occt_parallel.min << ','
          << r.occt_parallel.max << ','
          << (r.timed_imported_only ? r.occt_serial_imported.median : r.occt_serial.median) << ',' << r.our_triangles
          << ',' << r.occt_triangles << ',' << r.occt_triangles_all << ',' << r.occt_triangles_default_angle << ','
          << r.capped << ',' << r.inconsistencies << ',' << r.our_dev.max << ',' << r.our_dev.mean() << ','
          << r.occt_dev.max << ',' << r.occt_dev.mean() << ',' << r.occt_status << '\n';
    }
  }
  {
    // nlohmann (report::Json keeps key order): the same keys as the hand-written schema-1 file, plus the
    // standard header (schema_version, program, kind, commit).
    report::Json doc = report::document("brepmesh_comparison", 2, "measured", FRONTSTEAL_GIT_COMMIT);
    doc["date"] = date;
    doc["machine"] = frontsteal::cpu_model();
    doc["hardware_threads"] = std::thread::hardware_concurrency();
    doc["load_average_before"] = load_before;
    doc["load_average_after"] = load_after;
    doc["repeats"] = o.repeats;
    doc["angle_rad"] = o.angle;
    doc["max_steps"] = o.max_steps;
    doc["time_unit"] = "ms";
    auto timing_json = [](const Timing& t) {
      return report::Json{{"median", t.median}, {"min", t.min}, {"max", t.max}};
    };
    report::Json out_rows = report::Json::array();
    for (const Row& r : rows) {
      report::Json ours{{"ms", timing_json(r.ours)},
                        {"triangles", r.our_triangles},
                        {"capped", r.capped},
                        {"inconsistencies", r.inconsistencies},
                        {"partial_cells", r.partial_cells},
                        {"constrained_pieces", r.constrained_pieces},
                        {"dev_max", r.our_dev.max},
                        {"dev_mean", r.our_dev.mean()},
                        {"samples", r.our_dev.samples},
                        {"vertex_residual_max", r.our_dev.vertex_max}};
      report::Json occt{
          {"ms_1t", timing_json(r.occt_serial)},
          {"ms_parallel", timing_json(r.occt_parallel)},
          {"ms_1t_compared_faces", r.timed_imported_only ? timing_json(r.occt_serial_imported) : report::Json()},
          {"triangles_compared", r.occt_triangles},
          {"triangles_all", r.occt_triangles_all},
          {"triangles_parallel_compared", r.occt_triangles_parallel},
          {"triangles_default_angle_compared", r.occt_triangles_default_angle},
          {"edge_tolerance_max", r.edge_tolerance},
          {"status", r.occt_status},
          {"dev_max", r.occt_dev.max},
          {"dev_mean", r.occt_dev.mean()},
          {"samples", r.occt_dev.samples},
          {"vertex_residual_max", r.occt_dev.vertex_max}};
      out_rows.push_back({{"file", r.file},
                          {"faces", r.faces},
                          {"faces_compared", r.faces_compared},
                          {"surfaces", r.surfaces},
                          {"trimmed", r.trimmed},
                          {"diagonal", r.diagonal},
                          {"eps_fraction", r.eps_fraction},
                          {"eps", r.eps},
                          {"import_ms", r.import_ms},
                          {"ours", std::move(ours)},
                          {"brepmesh", std::move(occt)}});
    }
    doc["rows"] = std::move(out_rows);
    std::ofstream(dir / "brepmesh.json") << doc.dump(2) << '\n';
  }
}

}  // namespace frontsteal::brepmesh
