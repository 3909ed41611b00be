// mpi_workload.hpp — the read-only workload every rank builds identically: the tessellation scenes along the
// camera path of frontsteal, or a synthetic cost shape (synthetic_cost.hpp: synthetic:N, cascade:N).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "distributed/mpi_options.hpp"
#include "distributed/synthetic_cost.hpp"
#include "tessellate/frame_workload.hpp"
#include "tessellate/path_scene.hpp"

namespace frontsteal::mpi {

struct Workload {
  ItemId n = 0;
  std::string kind;                                        // "synthetic", "cascade" or "tessellation"
  std::function<std::uint32_t(int frame, ItemId id)> run;  // executes item id of frame f; its triangles
  // The same on the rank's worker thread w (hier: --threads workers, each with its own tessellation scratch).
  std::function<std::uint32_t(int frame, ItemId id, WorkerId w)> run_on;
  std::function<std::uint64_t(int frame)> serial_triangles;  // the serial loop's count for frame f (rank 0)
  // Tessellation (empty for synthetic): the scene along frontsteal's default path (tessellate/path_scene.hpp);
  // one scratch per worker thread of the rank (--threads).
  tess::PathScene scene;
  std::optional<tess::FrameWorkload> frames;  // over scene
  std::vector<std::uint64_t> serial;          // per frame, the serial loop's triangles (rank 0)
  std::optional<SyntheticCost> cost;          // synthetic shapes: every item's cost, every frame
};

// Fills wl (in place: its closures point into it). Rank 0 also runs the serial reference loop.
void build_workload(const Options& o, int rank, Workload& wl);

}  // namespace frontsteal::mpi
