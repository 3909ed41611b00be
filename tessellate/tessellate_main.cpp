// tessellate_main.cpp — frontsteal-tessellate: the tessellator alone, on a scene and its camera path. It
// audits every frame (the per-surface audit of surface_tessellator.hpp, step 6: pieces tiled exactly, areas
// equal to the trim loops', tracing complete; and surfaces held at the step cap), and exports a frame as OBJ
// or PLY. The committed audit of the default scene (results/tessellate/) is its output.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "measure/machine_info.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/mesh_export.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"
#include "tessellate/triangle_budget.hpp"

namespace {

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;
namespace report = frontsteal::report;

constexpr const char* kProgram = "frontsteal-tessellate";
constexpr const char* kDescription =
    R"(Tessellates a scene along the main job's camera path (orbit, then zoom) on one thread and audits every
surface of every frame: trimmed pieces tiled exactly by their triangles (no overlap, no covered hole, no
gap), each trimmed surface's (u, v) area equal to its trim loops', tracing complete; surfaces whose step
count was held at the cap (their deviation may exceed the tolerance) are counted. Prints a per-frame table,
writes tessellate-audit.{md,csv,json}, and with --export writes one frame's mesh.)";
constexpr const char* kFooter = R"(
Exit status: 0 when every surface passes the audit, 1 when any fails, 2 for bad usage.)";

struct Options {
  std::string scene = "plant:15906";
  int frames = 24;
  double tolerance = 1.0;
  int width = 1280, height = 720;
  int max_steps = 256;
  std::uint64_t max_triangles = 0;  // 0: no budget
  std::string export_file;
  int export_frame = 0;
  std::string plot_surface;
  ts::PlantedDefect planted_defect = ts::PlantedDefect::none;
  std::string out = "out";
  bool quiet = false;
};

Options parse(int argc, char** argv) {
  Options o;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--scene", o.scene, "teapot | teacup | teaspoon | plant:N[:seed] | a model file");
  cli.option("--frames", o.frames, "frames along the path")->check(CLI::Range(1, 100000));
  cli.option("--tolerance", o.tolerance, "screen-space tolerance in pixels")->check(CLI::Range(0.01, 1000.0));
  std::string size = "1280x720";
  cli.option("--size", size, "image size")->check(report::size_validator());
  cli.option("--max-steps", o.max_steps, "step cap per direction and patch")->check(CLI::Range(1, 4096));
  cli.option("--max-triangles", o.max_triangles,
             "triangle budget per frame: the predicted count is capped by coarsening the surfaces farthest from "
             "the eye first (triangle_budget.hpp); 0: no budget")
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 40));
  cli.option("--export", o.export_file,
             "also write frame --frame as FILE (.obj: text, 9 significant digits, exact "
             "for the float buffers; .ply: binary floats)")
      ->check([](const std::string& f) {
        const std::string ext = fsys::path(f).extension().string();
        return ext == ".obj" || ext == ".ply" ? std::string() : "expects a .obj or .ply file, got '" + f + "'";
      });
  cli.option("--frame", o.export_frame, "the frame to export and to plot")->check(CLI::Range(0, 100000));
  cli.option("--plot-surface", o.plot_surface,
             "also plot surface N's triangles in (u, v) at frame --frame (gnuplot "
             "PNG, filled at half opacity: a region covered twice shows darker, a covered hole shows)");
  std::string defect = "none";
  cli.option("--plant-defect", defect,
             "negative control: tessellate with a planted defect (wave1-bridge | drop-ear) "
             "to see the audit fail (exit 1)")
      ->check(CLI::IsMember({"none", "wave1-bridge", "drop-ear"}));
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  std::tie(o.width, o.height) = report::parse_size(size);
  o.planted_defect = ts::planted_defect_named(defect).value_or(ts::PlantedDefect::none);
  if (o.export_frame >= o.frames) cli.usage_error("--frame must be below --frames");
  return o;
}

struct FrameAudit {
  int frame = 0;
  std::uint64_t visible = 0, trimmed = 0, partial_cells = 0, triangles = 0;
  std::uint64_t trace_failures = 0, tiling_violations = 0, area_mismatches = 0, inconsistent_surfaces = 0, capped = 0;
  double ms = 0;
  std::string first_inconsistent;
  ts::BudgetOutcome budget;  // with --max-triangles only
};

// The surface's triangles in (u, v) as filled half-transparent polygons: gnuplot data, script and PNG.
void plot_uv_triangles(const Options& o, const report::ResultsDir& dir, const std::string& name,
                       const ts::TriangleBuffers& b) {
  const std::string stem = "uv-" + name;
  std::ostringstream dat;
  dat << std::setprecision(9);
  for (std::size_t t = 0; t < b.indices.size(); t += 3) {
    for (int c = 0; c <= 3; ++c) {
      const glm::vec2 uv = b.uvs[b.indices[t + static_cast<std::size_t>(c % 3)]];
      dat << uv.x << ' ' << uv.y << '\n';
    }
    dat << '\n';
  }
  dir.write(stem + ".dat", dat.str());
  const char* defect = o.planted_defect == ts::PlantedDefect::none ? "" : " (PLANTED DEFECT, negative control)";
  std::ostringstream gp;
  gp << "set output '" << stem << ".png'\nset size square\n"
     << "set xrange [0:1]\nset yrange [0:1]\nset xlabel 'u'\nset ylabel 'v'\n"
     << "set title \"" << name << ", frame " << o.export_frame << ": " << b.triangle_count() << " triangles in (u, v)"
     << defect << "\\ndarker = covered twice\" noenhanced\n"
     << "plot '" << stem << ".dat' with filledcurves closed fs transparent solid 0.5 lc rgb '#3060c0' notitle, "
     << "'' with lines lc rgb '#102040' lw 0.5 notitle\n";
  dir.write_gnuplot(stem + ".gp", {800, 800, ""}, gp.str());
  dir.plot(stem + ".gp");
}

// Tessellates every frame of the path on this thread, auditing each surface; writes the export and the
// (u, v) plot at --frame.
std::vector<FrameAudit> audit_path(const Options& o, const ts::Model& model, const report::ResultsDir& dir) {
  std::vector<ts::PreparedSurface> prepared;
  for (const ts::Surface& s : model.surfaces) prepared.push_back(ts::prepare_surface(s));
  ts::TessellationSettings settings;
  settings.pixel_tolerance = o.tolerance;
  settings.max_steps = o.max_steps;
  settings.planted_defect = o.planted_defect;
  std::size_t plotted = model.surfaces.size();
  for (std::size_t k = 0; k < model.surfaces.size() && !o.plot_surface.empty(); ++k) {
    if (model.surfaces[k].name == o.plot_surface) plotted = k;
  }
  if (!o.plot_surface.empty() && plotted == model.surfaces.size()) {
    throw std::invalid_argument("no surface named '" + o.plot_surface + "' in " + o.scene);
  }
  const ts::Box box = ts::model_box(model);
  ts::TessellationScratch scratch;
  std::vector<ts::TriangleBuffers> buffers(model.surfaces.size());
  std::vector<ts::SurfacePlan> plans(o.max_triangles > 0 ? prepared.size() : 0);
  std::vector<FrameAudit> frames;
  for (int f = 0; f < o.frames; ++f) {
    const ts::Camera cam = ts::camera_on_path(box, f, o.frames, o.width, o.height);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    FrameAudit a;
    a.frame = f;
    const auto t0 = std::chrono::steady_clock::now();
    // With a budget, the whole frame is planned first, so that the budget can see every surface's count.
    if (o.max_triangles > 0) {
      for (std::size_t k = 0; k < prepared.size(); ++k)
        plans[k] = ts::plan_surface(prepared[k], cam, frustum, settings);
      a.budget = ts::apply_triangle_budget(prepared, plans, cam, settings, o.max_triangles);
    }
    for (std::size_t k = 0; k < prepared.size(); ++k) {
      const ts::SurfaceResult r =
          o.max_triangles > 0 ? ts::tessellate_planned(prepared[k], plans[k], settings, scratch, buffers[k])
                              : ts::tessellate_surface(prepared[k], cam, frustum, settings, scratch, buffers[k]);
      if (r.culled != ts::Culled::no) continue;
      ++a.visible;
      a.trimmed += prepared[k].trimmed();
      a.partial_cells += r.partial_cells;
      a.triangles += r.triangles;
      a.trace_failures += r.trace_failures;
      a.tiling_violations += r.tiling_violations;
      a.area_mismatches += r.area_mismatches;
      a.capped += r.capped;
      if (r.inconsistencies() > 0 && a.inconsistent_surfaces++ == 0) a.first_inconsistent = model.surfaces[k].name;
    }
    a.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (f == o.export_frame && plotted < buffers.size())
      plot_uv_triangles(o, dir, model.surfaces[plotted].name, buffers[plotted]);
    if (f == o.export_frame && !o.export_file.empty()) {
      std::vector<ts::MeshPart> parts;
      for (std::size_t k = 0; k < buffers.size(); ++k) parts.push_back({model.surfaces[k].name, &buffers[k]});
      ts::write_mesh_file(o.export_file, parts);
      if (!o.quiet) std::cerr << kProgram << ": frame " << f << " written to " << o.export_file << '\n';
    }
    if (!o.quiet) {
      std::cerr << kProgram << ": frame " << f + 1 << "/" << o.frames << ": " << a.triangles << " triangles, "
                << a.inconsistent_surfaces << " surfaces failing the audit\n";
    }
    frames.push_back(a);
  }
  return frames;
}

report::Table audit_table(const Options& o, const std::vector<FrameAudit>& frames) {
  std::vector<report::Column> columns = {{"frame", "frame"},
                                         {"visible", "visible"},
                                         {"trimmed", "trimmed"},
                                         {"partial_cells", "partial cells"},
                                         {"triangles", "triangles"},
                                         {"trace_failures", "trace failures"},
                                         {"tiling_violations", "tiling violations"},
                                         {"area_mismatches", "area mismatches"},
                                         {"failing_surfaces", "failing surfaces"},
                                         {"capped", "capped"},
                                         {"ms", "ms (1 thread, audit included)"}};
  if (o.max_triangles > 0) {
    columns.insert(
        columns.end(),
        {{"budget", "budget"}, {"predicted", "predicted"}, {"budget_met", "met"}, {"coarsened", "coarsened surfaces"}});
  }
  report::Table table(columns);
  for (const FrameAudit& a : frames) {
    std::vector<report::Cell> row = {a.frame,
                                     a.visible,
                                     a.trimmed,
                                     a.partial_cells,
                                     a.triangles,
                                     a.trace_failures,
                                     a.tiling_violations,
                                     a.area_mismatches,
                                     a.inconsistent_surfaces,
                                     a.capped,
                                     report::Cell::fixed(a.ms, 1)};
    if (o.max_triangles > 0) {
      row.insert(row.end(), {o.max_triangles, a.budget.predicted_after, a.budget.met, a.budget.coarsened});
    }
    table.add_row(std::move(row));
  }
  return table;
}

// Prints the summary and the table; writes tessellate-audit.{md,csv,json}. Returns the failing surface-frames.
std::uint64_t write_report(const Options& o, const ts::Model& model, const std::vector<FrameAudit>& frames,
                           const report::ResultsDir& dir, const std::string& load_before) {
  std::uint64_t failing = 0, capped = 0, checked = 0;
  for (const FrameAudit& a : frames) failing += a.inconsistent_surfaces, capped += a.capped, checked += a.trimmed;
  const report::Table table = audit_table(o, frames);
  std::ostringstream summary;
  summary << "Scene `" << o.scene << "` (" << model.surfaces.size() << " surfaces), " << o.frames
          << " frames along the "
          << "camera path (orbit, then zoom), " << o.width << "x" << o.height << ", tolerance " << o.tolerance
          << " px, step cap " << o.max_steps << ". Machine: " << frontsteal::cpu_model() << " ("
          << std::thread::hardware_concurrency() << " hardware threads), 1-minute load average " << load_before
          << " before and " << frontsteal::load_average_1min() << " after the run (frame times are disturbed when it "
          << "exceeds 1); commit " << FRONTSTEAL_GIT_COMMIT << ". Audit: " << checked
          << " trimmed surface-frames checked, " << failing << " failing; surfaces held at the step cap: " << capped
          << " surface-frames.";
  if (o.max_triangles > 0) {
    summary << " Triangle budget " << o.max_triangles << " per frame: the predicted count is capped by halving the "
            << "steps of the surfaces farthest from the eye first (triangle counts of trimmed surfaces are estimates).";
  }
  summary << "\n";
  std::cout << summary.str() << '\n' << table.terminal();
  dir.write("tessellate-audit.md",
            "# Tessellation audit along the camera path (measured)\n\n" + summary.str() + '\n' + table.markdown());
  dir.write("tessellate-audit.csv", table.csv());
  report::Json doc = report::document(kProgram, 1, "measured", FRONTSTEAL_GIT_COMMIT);
  doc["scene"] = o.scene;
  doc["surfaces"] = model.surfaces.size();
  doc["frames"] = o.frames;
  doc["tolerance_px"] = o.tolerance;
  doc["image"] = {o.width, o.height};
  doc["max_steps"] = o.max_steps;
  doc["max_triangles"] = o.max_triangles;
  doc["trimmed_surface_frames"] = checked;
  doc["failing_surface_frames"] = failing;
  doc["capped_surface_frames"] = capped;
  doc["per_frame"] = table.json();
  dir.write_json("tessellate-audit.json", doc);
  for (const FrameAudit& a : frames) {
    if (a.inconsistent_surfaces > 0) {
      std::cerr << kProgram << ": AUDIT FAILED: frame " << a.frame << ": " << a.inconsistent_surfaces
                << " surfaces (first: " << a.first_inconsistent << ")\n";
    }
  }
  return failing;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  ts::Model model;
  try {
    model = ts::load_scene(o.scene, FRONTSTEAL_DATA_DIR);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": cannot load scene '" << o.scene << "': " << e.what() << '\n';
    return 2;
  }
  try {
    const report::ResultsDir dir(kProgram, o.out);
    const std::string load_before = frontsteal::load_average_1min();
    const std::vector<FrameAudit> frames = audit_path(o, model, dir);
    return write_report(o, model, frames, dir, load_before) > 0 ? 1 : 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
}
