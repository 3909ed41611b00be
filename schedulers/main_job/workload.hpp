// workload.hpp — the main job's workload: the scene loaded and prepared once with its camera path
// (Workload), and the serial warm-up pass that sets the reference triangle counts (warm_up).
//
// Why apart from the main: the measurement (run.hpp) and the report read the same Workload; how it
// is made is one concept, the timing loops another.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/id_range.hpp"
#include "schedulers/main_job/limit_arm.hpp"
#include "schedulers/main_job/options.hpp"
#include "schedulers/registry.hpp"
#include "tessellate/frame_workload.hpp"
#include "tessellate/path_scene.hpp"

namespace frontsteal::main_job {

namespace sc = frontsteal::sched;

// The workload: the scene prepared once, its per-frame views, and one output buffer per surface.
// The scene along --path (tessellate/path_scene.hpp; every scheduler writes the same per-surface buffers),
// and what the serial loop found in it: the reference every scheduler's frames are audited against.
struct Workload : ts::PathScene {
  std::vector<std::uint64_t> serial_triangles;        // per frame, from the serial loop: the reference
  std::vector<std::uint64_t> serial_inconsistencies;  // per frame: surfaces whose tessellation audit failed
  std::vector<std::uint64_t> serial_capped;           // per frame: surfaces held at the step cap
  std::vector<std::uint64_t> serial_remade;           // per frame: surfaces re-tessellated (all without --reuse)
};

struct PreparedScene {
  Workload wl;
  sc::WorkloadHints hints;
};

PreparedScene prepare_scene(const Options& o, unsigned cores);

// Every run writes its items through the one frame workload of tessellate/frame_workload.hpp: the triangle
// counts and audit flags the audits need, per surface.
using FrameTessellator = ts::FrameWorkload;

// The serial warm-up pass: the reference triangle counts (and audit counts) per frame into `wl`, and per frame
// and surface the measured time (ns) and the cost estimate, for the round-robin cost spread
// (round_robin_spread.hpp).
struct WarmUp {
  std::vector<std::vector<double>> item_ns, item_estimate;
  double seconds = 0;  // the pass's wall time: about T1
};
// `limit` (when the run has a limit arm): its copies are grown beside the scene's buffers, surface by surface,
// untimed (limit_arm.hpp says why).
WarmUp warm_up(const Options& o, Workload& wl, FrameTessellator& tess, LimitCopies* limit);

}  // namespace frontsteal::main_job
