// workload.cpp — the main job's workload (workload.hpp): the scene's preparation and the
// serial warm-up pass.
#include "schedulers/main_job/workload.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "measure/machine_info.hpp"
#include "reporting/build_stamp.hpp"
#include "reporting/table.hpp"

namespace frontsteal::main_job {

namespace fs = frontsteal;
namespace report = frontsteal::report;

PreparedScene prepare_scene(const Options& o, unsigned cores) {
  PreparedScene scene;
  Workload& wl = scene.wl;
  const auto load_start = std::chrono::steady_clock::now();
  ts::PathSceneOptions po{.scene = o.scene,
                          .data_dir = FRONTSTEAL_DATA_DIR,
                          .path = o.path,
                          .frames = o.frames,
                          .width = o.width,
                          .height = o.height,
                          .settings = {}};
  po.settings.pixel_tolerance = o.tolerance;
  po.settings.planted_defect = o.planted_defect;
  try {
    static_cast<ts::PathScene&>(wl) = ts::make_path_scene(po);
  } catch (const std::exception& e) {
    std::cerr << kProgram << ": cannot load scene '" << o.scene << "': " << e.what() << '\n';
    std::exit(2);
  }
  const fs::ItemId n = wl.surfaces();
  // The hints of the cost- and locality-aware schedulers: patch centres, and the path's first (overview) view.
  scene.hints.centres = wl.centres();
  scene.hints.costs = wl.estimated_costs(0);
  const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  if (!o.quiet) {
    std::fprintf(stderr,
                 "frontsteal: scene %s: %u surfaces, %d frames (path %s), %s, %u hardware threads; "
                 "prepared in %.2f s\n",
                 o.scene.c_str(), n, o.frames, ts::name(o.path), fs::cpu_model().c_str(), cores, load_s);
  }
  return scene;
}

WarmUp warm_up(const Options& o, Workload& wl, FrameTessellator& tess, LimitCopies* limit) {
  const auto n = wl.model.surfaces.size();
  WarmUp w{std::vector<std::vector<double>>(o.frames, std::vector<double>(n)),
           std::vector<std::vector<double>>(o.frames, std::vector<double>(n)), 0};
  for (int f = 0; f < o.frames; ++f) {
    for (fs::ItemId id = 0; id < n; ++id) {
      w.item_estimate[f][id] = ts::estimate_cost(
          wl.prepared[id], ts::plan_surface(wl.prepared[id], wl.cameras[f], wl.frusta[f], wl.settings), wl.settings);
    }
  }
  tess.set_reuse(o.reuse);
  const auto warm_start = std::chrono::steady_clock::now();
  for (int f = 0; f < o.frames; ++f) {
    for (fs::ItemId id = 0; id < n; ++id) {
      const auto t0 = std::chrono::steady_clock::now();
      tess.run(f, id, 0);
      w.item_ns[f][id] = static_cast<double>(
          std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
      if (limit) limit->grow(f, id);
    }
    wl.serial_triangles.push_back(tess.frame_triangles());
    wl.serial_inconsistencies.push_back(tess.count_inconsistent());
    wl.serial_capped.push_back(tess.count_capped());
    wl.serial_remade.push_back(tess.count_remade());
    if (wl.serial_inconsistencies.back() > 0) {
      std::cerr << kProgram << ": frame " << f << ": " << wl.serial_inconsistencies.back()
                << " surfaces fail the tessellation audit (first: " << tess.first_inconsistent() << ")\n";
    }
  }
  w.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - warm_start).count();
  return w;
}

}  // namespace frontsteal::main_job
