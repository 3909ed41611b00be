// tessellate_main.cpp — frontsteal-tessellate: the tessellator alone, on a scene and its camera path. It
// audits every frame (the per-surface audit of surface_tessellator.hpp, step 6: pieces tiled exactly, areas
// equal to the trim loops', tracing complete; and surfaces held at the step cap), and exports a frame as OBJ
// or PLY. The committed audit of the default scene (tessellate/results/) is its output.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/cli_args.hpp"
#include "core/machine_info.hpp"
#include "tessellate/camera_path.hpp"
#include "tessellate/mesh_export.hpp"
#include "tessellate/scene_generator.hpp"
#include "tessellate/surface_tessellator.hpp"
#include "tessellate/triangle_budget.hpp"

#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif
#ifndef FRONTSTEAL_GIT_COMMIT
#define FRONTSTEAL_GIT_COMMIT "unknown"
#endif

namespace {

namespace ts = frontsteal::tess;
namespace fsys = std::filesystem;

constexpr std::string_view kProgram = "frontsteal-tessellate";
constexpr std::string_view kUsage = R"(usage: frontsteal-tessellate [options]

Tessellates a scene along the main job's camera path (orbit, then zoom) on one thread and audits every
surface of every frame: trimmed pieces tiled exactly by their triangles (no overlap, no covered hole, no
gap), each trimmed surface's (u, v) area equal to its trim loops', tracing complete; surfaces whose step
count was held at the cap (their deviation may exceed the tolerance) are counted. Prints a per-frame table,
writes tessellate-audit.{md,csv,json}, and with --export writes one frame's mesh. Exit status 1 when any
surface fails the audit, 2 for bad usage.

options:
  --scene S         teapot | teacup | teaspoon | plant:N[:seed] | a model file       (default plant:15906)
  --frames F        frames along the path                                              (default 24)
  --tolerance PX    screen-space tolerance in pixels                                   (default 1)
  --size WxH        image size                                                  (default 1280x720)
  --max-steps N     step cap per direction and patch                                   (default 256)
  --max-triangles N triangle budget per frame: the predicted count is capped by coarsening the surfaces
                    farthest from the eye first (triangle_budget.hpp); 0: no budget          (default 0)
  --export FILE     also write frame --frame as FILE (.obj: text, 9 significant digits, exact for the
                    float buffers; .ply: binary floats)
  --frame K         the frame to export and to plot                                    (default 0)
  --plot-surface N  also plot surface N's triangles in (u, v) at frame --frame (gnuplot PNG, filled at
                    half opacity: a region covered twice shows darker, a covered hole shows)
  --plant-defect D  negative control: tessellate with a planted defect (wave1-bridge | drop-ear) to see
                    the audit fail (exit 1)
  --out DIR         results directory                                                  (default out)
  --quiet           no progress lines
  --help            this text
)";

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
  namespace cli = frontsteal::cli;
  Options o;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--scene") {
      o.scene = args.value();
    } else if (a == "--frames") {
      o.frames = cli::parse_number<int>(kProgram, a, args.value(), 1, 100000);
    } else if (a == "--tolerance") {
      o.tolerance = cli::parse_number<double>(kProgram, a, args.value(), 0.01, 1000.0);
    } else if (a == "--size") {
      const std::string v(args.value());
      const auto x = v.find('x');
      if (x == std::string::npos) cli::usage_error(kProgram, "--size expects WxH, e.g. 1280x720, got '" + v + "'");
      o.width = cli::parse_number<int>(kProgram, "--size", std::string_view(v).substr(0, x), 16, 16384);
      o.height = cli::parse_number<int>(kProgram, "--size", std::string_view(v).substr(x + 1), 16, 16384);
    } else if (a == "--max-steps") {
      o.max_steps = cli::parse_number<int>(kProgram, a, args.value(), 1, 4096);
    } else if (a == "--max-triangles") {
      o.max_triangles = cli::parse_number<std::uint64_t>(kProgram, a, args.value(), 0, std::uint64_t{1} << 40);
    } else if (a == "--export") {
      o.export_file = args.value();
      const std::string ext = fsys::path(o.export_file).extension().string();
      if (ext != ".obj" && ext != ".ply") cli::usage_error(kProgram, "--export expects a .obj or .ply file, got '" + o.export_file + "'");
    } else if (a == "--frame") {
      o.export_frame = cli::parse_number<int>(kProgram, a, args.value(), 0, 100000);
    } else if (a == "--plot-surface") {
      o.plot_surface = args.value();
    } else if (a == "--plant-defect") {
      const std::string_view d = args.value();
      const auto defect = ts::planted_defect_named(d);
      if (!defect) cli::usage_error(kProgram, "--plant-defect expects wave1-bridge or drop-ear, got '" + std::string(d) + "'");
      o.planted_defect = *defect;
    } else if (a == "--out") {
      o.out = args.value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      cli::usage_error(kProgram, "unknown option '" + std::string(a) + "'");
    }
  }
  if (o.export_frame >= o.frames) cli::usage_error(kProgram, "--frame must be below --frames");
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
bool plot_uv_triangles(const Options& o, const std::string& name, const ts::TriangleBuffers& b) {
  const fsys::path dir(o.out);
  const std::string stem = "uv-" + name;
  {
    std::ofstream dat(dir / (stem + ".dat"));
    dat << std::setprecision(9);
    for (std::size_t t = 0; t < b.indices.size(); t += 3) {
      for (int c = 0; c <= 3; ++c) {
        const glm::vec2 uv = b.uvs[b.indices[t + static_cast<std::size_t>(c % 3)]];
        dat << uv.x << ' ' << uv.y << '\n';
      }
      dat << '\n';
    }
  }
  const char* defect = o.planted_defect == ts::PlantedDefect::none ? "" : " (PLANTED DEFECT, negative control)";
  std::ofstream(dir / (stem + ".gp"))
      << "# gnuplot script written by frontsteal-tessellate; run from " << o.out << "\n"
      << "set terminal pngcairo size 800,800\nset output '" << stem << ".png'\nset size square\n"
      << "set xrange [0:1]\nset yrange [0:1]\nset xlabel 'u'\nset ylabel 'v'\n"
      << "set title \"" << name << ", frame " << o.export_frame << ": " << b.triangle_count() << " triangles in (u, v)"
      << defect << "\\ndarker = covered twice\" noenhanced\n"
      << "plot '" << stem << ".dat' with filledcurves closed fs transparent solid 0.5 lc rgb '#3060c0' notitle, "
      << "'' with lines lc rgb '#102040' lw 0.5 notitle\n";
  const std::string command = "cd '" + o.out + "' && gnuplot '" + stem + ".gp'";
  if (std::system(command.c_str()) != 0) {
    std::cerr << kProgram << ": gnuplot failed or is missing (apt-get install gnuplot-nox); " << stem << ".gp is written\n";
  }
  return true;
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
  std::error_code ec;
  fsys::create_directories(o.out, ec);
  if (ec) {
    std::cerr << kProgram << ": cannot create " << o.out << ": " << ec.message() << '\n';
    return 1;
  }
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
    std::cerr << kProgram << ": no surface named '" << o.plot_surface << "' in " << o.scene << '\n';
    return 2;
  }
  const ts::Box box = ts::model_box(model);
  ts::TessellationScratch scratch;
  std::vector<ts::TriangleBuffers> buffers(model.surfaces.size());
  std::vector<ts::SurfacePlan> plans(o.max_triangles > 0 ? prepared.size() : 0);

  std::vector<FrameAudit> frames;
  const std::string load_before = frontsteal::load_average_1min();
  for (int f = 0; f < o.frames; ++f) {
    const ts::Camera cam = ts::camera_on_path(box, f, o.frames, o.width, o.height);
    const ts::Frustum frustum = ts::Frustum::of(cam);
    FrameAudit a;
    a.frame = f;
    const auto t0 = std::chrono::steady_clock::now();
    // With a budget, the whole frame is planned first, so that the budget can see every surface's count.
    if (o.max_triangles > 0) {
      for (std::size_t k = 0; k < prepared.size(); ++k) plans[k] = ts::plan_surface(prepared[k], cam, frustum, settings);
      a.budget = ts::apply_triangle_budget(prepared, plans, cam, settings, o.max_triangles);
    }
    for (std::size_t k = 0; k < prepared.size(); ++k) {
      const ts::SurfaceResult r = o.max_triangles > 0
                                      ? ts::tessellate_planned(prepared[k], plans[k], settings, scratch, buffers[k])
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
    if (f == o.export_frame && plotted < buffers.size()) {
      if (!plot_uv_triangles(o, model.surfaces[plotted].name, buffers[plotted])) return 1;
    }
    if (f == o.export_frame && !o.export_file.empty()) {
      std::vector<ts::MeshPart> parts;
      for (std::size_t k = 0; k < buffers.size(); ++k) parts.push_back({model.surfaces[k].name, &buffers[k]});
      try {
        ts::write_mesh_file(o.export_file, parts);
      } catch (const std::exception& e) {
        std::cerr << kProgram << ": " << e.what() << '\n';
        return 1;
      }
      if (!o.quiet) std::cerr << kProgram << ": frame " << f << " written to " << o.export_file << '\n';
    }
    if (!o.quiet) {
      std::cerr << kProgram << ": frame " << f + 1 << "/" << o.frames << ": " << a.triangles << " triangles, "
                << a.inconsistent_surfaces << " surfaces failing the audit\n";
    }
    frames.push_back(a);
  }

  // Report: one table, three files.
  std::uint64_t failing = 0, capped = 0, checked = 0;
  for (const FrameAudit& a : frames) failing += a.inconsistent_surfaces, capped += a.capped, checked += a.trimmed;
  std::ostringstream table;
  table << "| frame | visible | trimmed | partial cells | triangles | trace failures | tiling violations | area mismatches "
           "| failing surfaces | capped | ms (1 thread, audit included) |";
  if (o.max_triangles > 0) table << " budget | predicted | coarsened surfaces |";
  table << "\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|" << (o.max_triangles > 0 ? "---:|---:|---:|" : "") << "\n";
  for (const FrameAudit& a : frames) {
    table << "| " << a.frame << " | " << a.visible << " | " << a.trimmed << " | " << a.partial_cells << " | " << a.triangles
          << " | " << a.trace_failures << " | " << a.tiling_violations << " | " << a.area_mismatches << " | "
          << a.inconsistent_surfaces << " | " << a.capped << " | " << std::fixed << std::setprecision(1) << a.ms << " |";
    if (o.max_triangles > 0) {
      table << " " << o.max_triangles << " | " << a.budget.predicted_after << (a.budget.met ? "" : " (not met)") << " | "
            << a.budget.coarsened << " |";
    }
    table << "\n";
  }
  const std::string machine = frontsteal::cpu_model();
  std::ostringstream summary;
  summary << "Scene `" << o.scene << "` (" << model.surfaces.size() << " surfaces), " << o.frames << " frames along the "
          << "camera path (orbit, then zoom), " << o.width << "x" << o.height << ", tolerance " << o.tolerance
          << " px, step cap " << o.max_steps << ". Machine: " << machine << " (" << std::thread::hardware_concurrency()
          << " hardware threads), 1-minute load average " << load_before << " before and " << frontsteal::load_average_1min()
          << " after the run (frame times are disturbed when it exceeds 1); commit " << FRONTSTEAL_GIT_COMMIT
          << ". Audit: " << checked << " trimmed surface-frames checked, " << failing
          << " failing; surfaces held at the step cap: " << capped << " surface-frames.";
  if (o.max_triangles > 0) {
    summary << " Triangle budget " << o.max_triangles << " per frame: the predicted count is capped by halving the "
            << "steps of the surfaces farthest from the eye first (triangle counts of trimmed surfaces are estimates).";
  }
  summary << "\n";
  std::cout << summary.str() << '\n' << table.str();
  const fsys::path dir(o.out);
  std::ofstream(dir / "tessellate-audit.md") << "# Tessellation audit along the camera path (measured)\n\n"
                                             << summary.str() << '\n' << table.str();
  {
    std::ofstream csv(dir / "tessellate-audit.csv");
    csv << "frame,visible,trimmed,partial_cells,triangles,trace_failures,tiling_violations,area_mismatches,"
           "failing_surfaces,capped,ms\n";
    for (const FrameAudit& a : frames) {
      csv << a.frame << ',' << a.visible << ',' << a.trimmed << ',' << a.partial_cells << ',' << a.triangles << ','
          << a.trace_failures << ',' << a.tiling_violations << ',' << a.area_mismatches << ',' << a.inconsistent_surfaces
          << ',' << a.capped << ',' << a.ms << '\n';
    }
  }
  {
    std::ofstream js(dir / "tessellate-audit.json");
    js << "{\n  \"kind\": \"measured\", \"scene\": \"" << o.scene << "\", \"surfaces\": " << model.surfaces.size()
       << ", \"frames\": " << o.frames << ", \"tolerance_px\": " << o.tolerance << ", \"image\": [" << o.width << ", "
       << o.height << "], \"max_steps\": " << o.max_steps << ", \"max_triangles\": " << o.max_triangles
       << ", \"commit\": \"" << FRONTSTEAL_GIT_COMMIT
       << "\",\n  \"trimmed_surface_frames\": " << checked << ", \"failing_surface_frames\": " << failing
       << ", \"capped_surface_frames\": " << capped << ",\n  \"per_frame\": [\n";
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const FrameAudit& a = frames[k];
      js << "    {\"frame\": " << a.frame << ", \"visible\": " << a.visible << ", \"trimmed\": " << a.trimmed
         << ", \"partial_cells\": " << a.partial_cells << ", \"triangles\": " << a.triangles << ", \"trace_failures\": "
         << a.trace_failures << ", \"tiling_violations\": " << a.tiling_violations << ", \"area_mismatches\": "
         << a.area_mismatches << ", \"failing_surfaces\": " << a.inconsistent_surfaces << ", \"capped\": " << a.capped
         << ", \"ms\": " << a.ms;
      if (o.max_triangles > 0) {
        js << ", \"predicted\": " << a.budget.predicted_after << ", \"budget_met\": " << (a.budget.met ? "true" : "false")
           << ", \"coarsened\": " << a.budget.coarsened;
      }
      js << "}" << (k + 1 < frames.size() ? "," : "") << "\n";
    }
    js << "  ]\n}\n";
  }
  if (failing > 0) {
    for (const FrameAudit& a : frames) {
      if (a.inconsistent_surfaces > 0) {
        std::cerr << kProgram << ": AUDIT FAILED: frame " << a.frame << ": " << a.inconsistent_surfaces
                  << " surfaces (first: " << a.first_inconsistent << ")\n";
      }
    }
    return 1;
  }
  return 0;
}
