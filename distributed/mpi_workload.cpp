// mpi_workload.cpp — the workload of frontsteal-mpi (mpi_workload.hpp).
#include "distributed/mpi_workload.hpp"

#include <algorithm>

#include "core/synthetic_work.hpp"

#ifndef FRONTSTEAL_DATA_DIR
#define FRONTSTEAL_DATA_DIR "data"
#endif

namespace frontsteal::mpi {
namespace {

std::uint32_t synthetic_triangles(int frame, ItemId id) {
  return static_cast<std::uint32_t>((id * 2654435761u ^ static_cast<std::uint32_t>(frame) * 40503u) % 97u + 1u);
}

void build_synthetic(const Options& o, const SyntheticScene& scene, Workload& wl) {
  wl.kind = scene.prefix;
  wl.n = static_cast<ItemId>(scene.items);  // checked by parse_options()
  wl.cost.emplace(scene.shape, wl.n, o.frames, o.skew);
  const double unit_ns = o.work_ns;
  wl.run = [&wl, unit_ns](int f, ItemId id) {
    spin_work(static_cast<std::uint32_t>(wl.cost->units(f, id) * unit_ns + 0.5));
    return synthetic_triangles(f, id);
  };
  wl.run_on = [&wl](int f, ItemId id, WorkerId) { return wl.run(f, id); };
  wl.serial_triangles = [n = wl.n](int f) {
    std::uint64_t t = 0;
    for (ItemId id = 0; id < n; ++id) t += synthetic_triangles(f, id);
    return t;
  };
}

}  // namespace

void build_workload(const Options& o, int rank, Workload& wl) {
  if (const SyntheticScene s = parse_synthetic_scene(o.scene); s.synthetic) {
    build_synthetic(o, s, wl);
    return;
  }
  wl.kind = "tessellation";
  tess::PathSceneOptions so{.scene = o.scene, .data_dir = FRONTSTEAL_DATA_DIR, .frames = o.frames, .settings = {}};
  so.settings.pixel_tolerance = o.tolerance;
  wl.scene = tess::make_path_scene(so);  // throws on a bad or empty scene
  wl.n = wl.scene.surfaces();
  wl.frames.emplace(wl.scene, static_cast<WorkerId>(std::max(1, o.threads)));
  wl.run = [&wl](int f, ItemId id) { return wl.frames->run(f, id, 0).triangles; };
  wl.run_on = [&wl](int f, ItemId id, WorkerId w) { return wl.frames->run(f, id, w).triangles; };
  if (rank == 0) {  // the serial reference: a plain loop, once, before any scheduler runs
    for (int f = 0; f < o.frames; ++f) {
      std::uint64_t t = 0;
      for (ItemId id = 0; id < wl.n; ++id) t += wl.run(f, id);
      wl.serial.push_back(t);
    }
  }
  wl.serial_triangles = [&wl](int f) { return wl.serial[static_cast<std::size_t>(f)]; };
}

}  // namespace frontsteal::mpi
