// frontsteal-render — greedy rendering of a camera path (paper §5), headless: PNG frames, a lagging and a
// synchronized image of the same views with PSNR and SSIM, and the run's statistics (tessellations/s, updates/s,
// average and maximum lag, as in Table 2) as JSON, CSV, markdown and a gnuplot plot of the lag.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

#include "core/cli_args.hpp"
#include "render/greedy_renderer.hpp"
#include "render/headless_gl.hpp"
#include "render/render_scene.hpp"

namespace ts = frontsteal::tess;
namespace rd = frontsteal::render;

namespace {

constexpr std::string_view kProgram = "frontsteal-render";
constexpr std::string_view kUsage = R"(usage: frontsteal-render [options]

Greedy rendering (paper §5) of a camera path over a scene, headless (OpenGL through EGL; Mesa's llvmpipe when
there is no GPU). A pusher thread draws at the display rate and never waits; tessellators (the stealing
scheduler) re-tessellate the scene for the view current when their frame starts, and swap each connected
component's triangles in atomically. Writes PNG frames, lagging and synchronized images of the same views with
PSNR and SSIM, a side-by-side colour plate, and the statistics (render.json, render.csv, render.md, render-lag.png).

options:
  --scene S          teapot, teacup, teaspoon, plant:<N>[:seed] or a model file          (default plant:4101)
  --path P           walkthrough, zoom, orbit or orbit-then-zoom                          (default walkthrough)
  --updates N        pusher updates (one path frame each)                                 (default 150)
  --rate R           display rate the pusher aims at, updates/s; 0: as fast as it can      (default 30)
  --tessellators P   tessellator threads                                  (default cores - 1, at least 1)
  --slots K          triangle buffers per component (>= 2)                                  (default 3)
  --size WxH         image size                                                       (default 640x360)
  --tolerance PX     screen-space tessellation tolerance, pixels                              (default 1)
  --samples N        lagging/synchronized pairs for PSNR and SSIM                              (default 4)
  --png-every K      also save every K-th update's frame (0: none)                            (default 30)
  --single-thread    one thread: draw, then tessellate within the §5.3 budget 1/R - m*t_p
  --null-renderer    no OpenGL: count the triangles that would be drawn (CPU-only measurements)
  --out DIR          results directory                                              (default out/render)
  --quiet            no progress lines
  --help             this text

Cracks: components are swapped independently, so while the view moves a crack may open between two
components tessellated for different views (the paper accepts this, §5.2); inside a component, never.
)";

struct Options {
  std::string scene = "plant:4101";
  std::string out = "out/render";
  bool quiet = false;
  rd::GreedyOptions greedy;
};

ts::CameraPathKind parse_path(std::string_view v) {
  for (auto k : {ts::CameraPathKind::walkthrough, ts::CameraPathKind::zoom, ts::CameraPathKind::orbit,
                 ts::CameraPathKind::orbit_then_zoom}) {
    if (v == ts::name(k)) return k;
  }
  frontsteal::cli::usage_error(kProgram, "--path is walkthrough, zoom, orbit or orbit-then-zoom, got '" + std::string(v) + "'");
}

Options parse(int argc, char** argv) {
  Options o;
  namespace cli = frontsteal::cli;
  o.greedy.tessellators = std::max(1u, std::thread::hardware_concurrency() - 1);
  o.greedy.updates = 150;
  o.greedy.png_every = 30;
  cli::ArgReader args(argc, argv, kProgram, kUsage);
  while (args.next()) {
    const std::string_view a = args.flag();
    if (a == "--scene") {
      o.scene = args.value();
    } else if (a == "--path") {
      o.greedy.path = parse_path(args.value());
    } else if (a == "--updates") {
      o.greedy.updates = cli::parse_number<int>(kProgram, a, args.value(), 1, 1'000'000);
    } else if (a == "--rate") {
      o.greedy.display_rate = cli::parse_number<double>(kProgram, a, args.value(), 0, 10000);
    } else if (a == "--tessellators") {
      o.greedy.tessellators = cli::parse_number<frontsteal::WorkerId>(kProgram, a, args.value(), 1, 256);
    } else if (a == "--slots") {
      o.greedy.slots = cli::parse_number<std::uint32_t>(kProgram, a, args.value(), 2, 16);
    } else if (a == "--size") {
      const cli::Size size = cli::parse_size(kProgram, a, args.value(), 16, 8192);
      o.greedy.width = size.width;
      o.greedy.height = size.height;
    } else if (a == "--tolerance") {
      o.greedy.settings.pixel_tolerance = cli::parse_number<double>(kProgram, a, args.value(), 0.05, 100);
    } else if (a == "--samples") {
      o.greedy.samples = cli::parse_number<int>(kProgram, a, args.value(), 0, 100);
    } else if (a == "--png-every") {
      o.greedy.png_every = cli::parse_number<int>(kProgram, a, args.value(), 0, 1'000'000);
    } else if (a == "--single-thread") {
      o.greedy.single_thread = true;
    } else if (a == "--null-renderer") {
      o.greedy.null_renderer = true;
    } else if (a == "--out") {
      o.out = args.value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      cli::usage_error(kProgram, "unknown option '" + std::string(a) + "'");
    }
  }
  return o;
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  Options o = parse(argc, argv);
  const std::optional<ts::Model> loaded = rd::load_render_scene_or_report(kProgram, o.scene, FRONTSTEAL_DATA_DIR);
  if (!loaded) return 2;
  const ts::Model& model = *loaded;
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) {
    std::cerr << kProgram << ": cannot create " << o.out << ": " << ec.message() << '\n';
    return 2;
  }
  o.greedy.out_dir = o.out;
  if (!o.quiet) {
    int components = 0;
    for (const ts::Surface& s : model.surfaces) components = std::max(components, s.component + 1);
    o.greedy.progress = [](const std::string& line) { std::cerr << kProgram << ": " << line << '\n'; };
    std::cerr << kProgram << ": " << o.scene << " (" << model.surfaces.size() << " surfaces, " << components
              << " components), " << ts::name(o.greedy.path) << " path, " << o.greedy.updates << " updates at "
              << (o.greedy.display_rate > 0 ? fixed(o.greedy.display_rate, 0) + "/s" : std::string("full speed")) << '\n';
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

  // ---- results ---------------------------------------------------------------------------------------------
  std::ostringstream md, js, csv;
  md << "# Greedy rendering (measured)\n\n"
     << "Scene " << o.scene << " (" << model.surfaces.size() << " surfaces), " << ts::name(o.greedy.path) << " path, "
     << o.greedy.width << "x" << o.greedy.height << ", tolerance " << o.greedy.settings.pixel_tolerance << " px, "
     << o.greedy.slots << " slots per component. Commit " << FRONTSTEAL_GIT_COMMIT << ", "
     << std::thread::hardware_concurrency() << " hardware threads.\n\n"
     << "- renderer: " << st.renderer << "\n- mode: " << st.mode << "\n- display rate asked: "
     << (o.greedy.display_rate > 0 ? fixed(o.greedy.display_rate, 1) + " updates/s" : std::string("as fast as possible"))
     << "\n- tessellation audit (trimmed pieces tiled exactly, (u, v) area = trim-loop area): "
     << st.tessellation_inconsistencies << " failing surface tessellations"
     << "\n\n| updates/s | tessellations/s | surfaces/s | avg lag (frames) | max lag | triangles/update | driver waits | seconds |\n"
     << "|---|---|---|---|---|---|---|---|\n"
     << "| " << fixed(st.updates_per_second, 2) << " | " << fixed(st.tessellations_per_second, 2) << " | "
     << fixed(st.surfaces_per_second, 0) << " | " << fixed(st.mean_lag, 2) << " | " << st.max_lag << " | "
     << fixed(st.mean_triangles, 0) << " | " << st.driver_waits << " | " << fixed(st.seconds, 2) << " |\n";
  if (!st.quality.empty()) {
    md << "\nLagging (what the pusher drew) against synchronized (every surface tessellated for that very view):\n\n"
       << "| update | mean lag | PSNR (dB) | SSIM | images |\n|---|---|---|---|---|\n";
    for (const rd::QualitySample& q : st.quality) {
      md << "| " << q.update << " | " << fixed(q.mean_lag, 2) << " | " << fixed(q.psnr_db, 2) << " | " << fixed(q.ssim, 4)
         << " | " << std::filesystem::path(q.lagging_png).filename().string() << ", "
         << std::filesystem::path(q.synchronized_png).filename().string() << " |\n";
    }
    if (!st.colour_plate_png.empty()) md << "\nColour plate (left lagging, right synchronized): colour-plate.png\n";
  }
  js << "{\n  \"scene\": \"" << o.scene << "\", \"surfaces\": " << model.surfaces.size() << ", \"path\": \""
     << ts::name(o.greedy.path) << "\", \"width\": " << o.greedy.width << ", \"height\": " << o.greedy.height
     << ",\n  \"commit\": \"" << FRONTSTEAL_GIT_COMMIT << "\", \"hardware_threads\": " << std::thread::hardware_concurrency()
     << ",\n  \"renderer\": \"" << st.renderer << "\", \"mode\": \"" << st.mode << "\", \"display_rate\": "
     << o.greedy.display_rate << ", \"tessellators\": " << o.greedy.tessellators << ", \"slots\": " << o.greedy.slots
     << ",\n  \"measured\": true, \"updates\": " << st.updates << ", \"seconds\": " << st.seconds
     << ", \"updates_per_second\": " << st.updates_per_second << ", \"tessellations_per_second\": "
     << st.tessellations_per_second << ", \"surfaces_per_second\": " << st.surfaces_per_second
     << ", \"tessellation_frames\": " << st.tessellation_frames << ", \"mean_lag\": " << st.mean_lag
     << ", \"max_lag\": " << st.max_lag << ", \"mean_triangles\": " << st.mean_triangles << ", \"driver_waits\": "
     << st.driver_waits << ", \"tessellation_inconsistencies\": " << st.tessellation_inconsistencies
     << ",\n  \"quality\": [";
  for (std::size_t k = 0; k < st.quality.size(); ++k) {
    const rd::QualitySample& q = st.quality[k];
    js << (k ? ", " : "") << "{\"update\": " << q.update << ", \"mean_lag\": " << q.mean_lag << ", \"psnr_db\": "
       << (std::isfinite(q.psnr_db) ? fixed(q.psnr_db, 3) : std::string("null")) << ", \"ssim\": " << q.ssim << "}";
  }
  js << "]\n}\n";
  csv << "update,at_seconds,draw_ms,mean_lag,max_lag,triangles,uploads,budget_ms\n";
  for (const rd::UpdateRecord& r : st.per_update) {
    csv << r.update << ',' << r.at_seconds << ',' << r.draw_ms << ',' << r.mean_lag << ',' << r.max_lag << ','
        << r.triangles << ',' << r.uploads << ',' << r.budget_ms << '\n';
  }
  std::ofstream(o.out + "/render.md") << md.str();
  std::ofstream(o.out + "/render.json") << js.str();
  std::ofstream(o.out + "/render.csv") << csv.str();
  std::ofstream(o.out + "/render.gp")
      << "# gnuplot script written by frontsteal-render; run from " << o.out << ": gnuplot render.gp\n"
      << "set terminal pngcairo size 900,420\nset output 'render-lag.png'\nset datafile separator ','\n"
      << "set title 'Greedy rendering: lag of the drawn triangles behind the view (measured)'\n"
      << "set xlabel 'pusher update'\nset ylabel 'lag (frames)'\nset key top left\n"
      << "plot 'render.csv' every ::1 using 1:4 with lines lw 2 title 'mean over components', "
         "'' every ::1 using 1:5 with lines title 'max'\n";
  const std::string plot = "cd '" + o.out + "' && gnuplot render.gp 2>/dev/null";
  if (std::system(plot.c_str()) != 0 && !o.quiet) {
    std::cerr << kProgram << ": gnuplot failed or is missing (apt-get install gnuplot-nox); render.gp is written\n";
  }
  std::cout << md.str();
  if (!o.quiet) std::cerr << kProgram << ": wrote " << o.out << "/render.{md,json,csv}, render-lag.png and the PNG frames\n";
  if (st.tessellation_inconsistencies > 0) {
    std::cerr << kProgram << ": AUDIT FAILED: " << st.tessellation_inconsistencies
              << " surface tessellations failed their audit (overlapping triangles, covered holes or a wrong area)\n";
    return 1;
  }
  return 0;
}
