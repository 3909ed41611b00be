// frontsteal-render — greedy rendering of a camera path (paper §5), headless: PNG frames, a lagging and a
// synchronized image of the same views with PSNR and SSIM, and the run's statistics (tessellations/s, updates/s,
// average and maximum lag, as in Table 2) as JSON, CSV, markdown and a gnuplot plot of the lag.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <optional>
#include <thread>
#include <tuple>
#include <cmath>

#include "reporting/build_stamp.hpp"
#include "reporting/command_line.hpp"
#include "reporting/results_dir.hpp"
#include "reporting/table.hpp"
#include "render/greedy_renderer.hpp"
#include "render/headless_gl.hpp"
#include "render/render_scene.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;
namespace report = frontsteal::report;

namespace {

constexpr const char* kProgram = "frontsteal-render";
constexpr const char* kDescription =
    R"(Greedy rendering (paper §5) of a camera path over a scene, headless (OpenGL through EGL; Mesa's llvmpipe when
there is no GPU). A pusher thread draws at the display rate and never waits; tessellators (the stealing
scheduler) re-tessellate the scene for the view current when their frame starts, and swap each connected
component's triangles in atomically. Writes PNG frames, lagging and synchronized images of the same views with
PSNR and SSIM, a side-by-side colour plate, and the statistics (render.json, render.csv, render.md, render-lag.png).)";
constexpr const char* kFooter = R"(
Cracks: components are swapped independently, so while the view moves a crack may open between two
components tessellated for different views (the paper accepts this, §5.2); inside a component, never.
Exit status: 0, 1 when a tessellation fails its audit or the run fails, 2 for bad usage, 3 without OpenGL.)";

struct Options {
  std::string scene = "plant:4101";
  std::string out = "out/render";
  bool quiet = false;
  rd::GreedyOptions greedy;
};

Options parse(int argc, char** argv) {
  Options o;
  o.greedy.tessellators = std::max(2u, std::thread::hardware_concurrency()) - 1;  // 0 means unknown: one
  o.greedy.updates = 150;
  o.greedy.png_every = 30;
  report::CommandLine cli(kProgram, kDescription, kFooter);
  cli.option("--scene", o.scene, "teapot, teacup, teaspoon, plant:<N>[:seed] or a model file");
  std::string path = ts::name(o.greedy.path);
  cli.option("--path", path, "walkthrough, zoom, orbit or orbit-then-zoom")
      ->check(CLI::IsMember({"walkthrough", "zoom", "orbit", "orbit-then-zoom"}));
  cli.option("--updates", o.greedy.updates, "pusher updates (one path frame each)")->check(CLI::Range(1, 1'000'000));
  cli.option("--rate", o.greedy.display_rate, "display rate the pusher aims at, updates/s; 0: as fast as it can")
      ->check(CLI::Range(0.0, 10000.0));
  cli.option("--tessellators", o.greedy.tessellators, "tessellator threads (default cores - 1, at least 1)")
      ->check(CLI::Range(1u, 256u));
  cli.option("--slots", o.greedy.slots, "triangle buffers per component")->check(CLI::Range(2u, 16u));
  std::string size = std::to_string(o.greedy.width) + "x" + std::to_string(o.greedy.height);
  cli.option("--size", size, "image size")->check(report::size_validator());
  cli.option("--tolerance", o.greedy.settings.pixel_tolerance, "screen-space tessellation tolerance, pixels")
      ->check(CLI::Range(0.05, 100.0));
  cli.option("--samples", o.greedy.samples, "lagging/synchronized pairs for PSNR and SSIM")->check(CLI::Range(0, 100));
  cli.option("--png-every", o.greedy.png_every, "also save every K-th update's frame (0: none)")
      ->check(CLI::Range(0, 1'000'000));
  cli.flag("--single-thread", o.greedy.single_thread,
           "one thread: draw, then tessellate within the §5.3 budget 1/R - m*t_p");
  cli.flag("--null-renderer", o.greedy.null_renderer,
           "no OpenGL: count the triangles that would be drawn (CPU-only measurements)");
  bool no_reuse = false;
  cli.flag("--no-reuse", no_reuse,
           "tessellate every surface every frame; by default a surface whose steps and trim polylines did not "
           "change keeps its triangles (the same bytes), as the paper's renderer does");
  cli.out(o.out);
  cli.quiet(o.quiet);
  cli.parse(argc, argv);
  for (auto k : {ts::CameraPathKind::walkthrough, ts::CameraPathKind::zoom, ts::CameraPathKind::orbit,
                 ts::CameraPathKind::orbit_then_zoom}) {
    if (path == ts::name(k)) o.greedy.path = k;
  }
  std::tie(o.greedy.width, o.greedy.height) = report::parse_size(size);
  o.greedy.reuse = !no_reuse;
  return o;
}

using report::fixed_text;

report::Table summary_table(const rd::GreedyStats& st) {
  report::Table t({{"updates_per_second", "updates/s"},
                   {"tessellations_per_second", "tessellations/s"},
                   {"surfaces_per_second", "surfaces/s"},
                   {"mean_lag", "avg lag (frames)"},
                   {"max_lag", "max lag"},
                   {"mean_triangles", "triangles/update"},
                   {"driver_waits", "driver waits"},
                   {"seconds", "seconds"}});
  t.add_row({report::Cell::fixed(st.updates_per_second, 2), report::Cell::fixed(st.tessellations_per_second, 2),
             report::Cell::fixed(st.surfaces_per_second, 0), report::Cell::fixed(st.mean_lag, 2), st.max_lag,
             report::Cell::fixed(st.mean_triangles, 0), st.driver_waits, report::Cell::fixed(st.seconds, 2)});
  return t;
}

std::string remade_text(const rd::GreedyStats& st, std::size_t surfaces, bool reuse) {
  const double per_frame =
      static_cast<double>(st.surfaces_remade) / static_cast<double>(std::max<std::uint64_t>(st.tessellation_frames, 1));
  return fixed_text(per_frame, 0) + " of " + std::to_string(surfaces) +
         (reuse ? " (reuse on: the others kept their triangles)" : " (--no-reuse: every surface every frame)");
}

report::Table quality_table(const rd::GreedyStats& st) {
  report::Table t({{"update", "update"},
                   {"mean_lag", "mean lag"},
                   {"psnr_db", "PSNR (dB)"},
                   {"ssim", "SSIM"},
                   {"images", "images", false}});
  for (const rd::QualitySample& q : st.quality) {
    const report::Json psnr = std::isfinite(q.psnr_db) ? report::Json(q.psnr_db) : report::Json(nullptr);
    t.add_row({q.update, report::Cell::fixed(q.mean_lag, 2), report::Cell::shown_as(fixed_text(q.psnr_db, 2), psnr),
               report::Cell::fixed(q.ssim, 4),
               std::filesystem::path(q.lagging_png).filename().string() + ", " +
                   std::filesystem::path(q.synchronized_png).filename().string()});
  }
  return t;
}

report::Table update_table(const rd::GreedyStats& st) {
  report::Table t({{"update", "update"},
                   {"at_seconds", "at (s)"},
                   {"draw_ms", "draw (ms)"},
                   {"mean_lag", "mean lag"},
                   {"max_lag", "max lag"},
                   {"triangles", "triangles"},
                   {"uploads", "uploads"},
                   {"budget_ms", "budget (ms)"}});
  for (const rd::UpdateRecord& r : st.per_update) {
    t.add_row({r.update, report::Cell::fixed(r.at_seconds, 3), report::Cell::fixed(r.draw_ms, 3),
               report::Cell::fixed(r.mean_lag, 2), r.max_lag, r.triangles, r.uploads,
               report::Cell::fixed(r.budget_ms, 3)});
  }
  return t;
}

// render.{md,json,csv}, render.gp and its PNG; the markdown is printed too.
void write_results(const Options& o, const ts::Model& model, const rd::GreedyStats& st, const report::ResultsDir& dir) {
  std::ostringstream md;
  md << "# Greedy rendering (measured)\n\n"
     << "Scene " << o.scene << " (" << model.surfaces.size() << " surfaces), " << ts::name(o.greedy.path) << " path, "
     << o.greedy.width << "x" << o.greedy.height << ", tolerance " << o.greedy.settings.pixel_tolerance << " px, "
     << o.greedy.slots << " slots per component. Commit " << FRONTSTEAL_GIT_COMMIT << ", "
     << std::thread::hardware_concurrency() << " hardware threads.\n\n"
     << "- renderer: " << st.renderer << "\n- mode: " << st.mode << "\n- display rate asked: "
     << (o.greedy.display_rate > 0 ? fixed_text(o.greedy.display_rate, 1) + " updates/s"
                                   : std::string("as fast as possible"))
     << "\n- tessellation audit (trimmed pieces tiled exactly, (u, v) area = trim-loop area): "
     << st.tessellation_inconsistencies << " failing surface tessellations"
     << "\n- surfaces re-tessellated per tessellation frame: " << remade_text(st, model.surfaces.size(), o.greedy.reuse)
     << "\n\n"
     << summary_table(st).markdown();
  if (!st.quality.empty()) {
    md << "\nLagging (what the pusher drew) against synchronized (every surface tessellated for that very view):\n\n"
       << quality_table(st).markdown();
    if (!st.colour_plate_png.empty()) md << "\nColour plate (left lagging, right synchronized): colour-plate.png\n";
  }
  report::Json js = report::document(kProgram, 2, "measured", FRONTSTEAL_GIT_COMMIT);
  js["scene"] = o.scene;
  js["surfaces"] = model.surfaces.size();
  js["path"] = ts::name(o.greedy.path);
  js["width"] = o.greedy.width;
  js["height"] = o.greedy.height;
  js["hardware_threads"] = std::thread::hardware_concurrency();
  js["renderer"] = st.renderer;
  js["mode"] = st.mode;
  js["display_rate"] = o.greedy.display_rate;
  js["tessellators"] = o.greedy.tessellators;
  js["slots"] = o.greedy.slots;
  js["updates"] = st.updates;
  js["tessellation_frames"] = st.tessellation_frames;
  js["tessellation_inconsistencies"] = st.tessellation_inconsistencies;
  js["reuse"] = o.greedy.reuse;
  js["surfaces_remade"] = st.surfaces_remade;
  const report::Json summary = summary_table(st).json()[0];
  for (auto it = summary.begin(); it != summary.end(); ++it) js[it.key()] = it.value();
  js["quality"] = quality_table(st).json();
  dir.write("render.md", md.str());
  dir.write_json("render.json", js);
  dir.write("render.csv", update_table(st).csv());
  dir.write_gnuplot("render.gp", {900, 420, ""},
                    "set output 'render-lag.png'\nset datafile separator ','\n"
                    "set title 'Greedy rendering: lag of the drawn triangles behind the view (measured)'\n"
                    "set xlabel 'pusher update'\nset ylabel 'lag (frames)'\nset key top left\n"
                    "plot 'render.csv' every ::1 using 1:4 with lines lw 2 title 'mean over components', "
                    "'' every ::1 using 1:5 with lines title 'max'\n");
  dir.plot("render.gp");
  std::cout << md.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options o = parse(argc, argv);
  const std::optional<ts::Model> loaded = rd::load_render_scene_or_report(kProgram, o.scene, FRONTSTEAL_DATA_DIR);
  if (!loaded) return 2;
  const ts::Model& model = *loaded;
  std::optional<report::ResultsDir> dir;
  try {
    dir.emplace(kProgram, o.out);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 2;
  }
  o.greedy.out_dir = o.out;
  if (!o.quiet) {
    int components = 0;
    for (const ts::Surface& s : model.surfaces) components = std::max(components, s.component + 1);
    o.greedy.progress = [](const std::string& line) { std::cerr << kProgram << ": " << line << '\n'; };
    std::cerr << kProgram << ": " << o.scene << " (" << model.surfaces.size() << " surfaces, " << components
              << " components), " << ts::name(o.greedy.path) << " path, " << o.greedy.updates << " updates at "
              << (o.greedy.display_rate > 0 ? fixed_text(o.greedy.display_rate, 0) + "/s" : std::string("full speed"))
              << '\n';
  }
  rd::GreedyStats st;
  try {
    st = rd::run_greedy(model, o.greedy);
  } catch (const rd::GraphicsError& e) {
    std::cerr << kProgram << ": " << e.what() << "\n(--null-renderer runs without OpenGL)\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }

  try {
    write_results(o, model, st, *dir);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": " << e.what() << '\n';
    return 1;
  }
  if (!o.quiet)
    std::cerr << kProgram << ": wrote " << o.out << "/render.{md,json,csv}, render-lag.png and the PNG frames\n";
  if (st.tessellation_inconsistencies > 0) {
    std::cerr << kProgram << ": AUDIT FAILED: " << st.tessellation_inconsistencies
              << " surface tessellations failed their audit (overlapping triangles, covered holes or a wrong area)\n";
    return 1;
  }
  return 0;
}
