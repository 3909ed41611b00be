// surface_reuse.hpp — frame-to-frame reuse of a surface's triangles, as the paper's renderer does: a surface
// whose step counts (and trim polylines) did not change since its buffer was made keeps that buffer.
//
// Why it is exact: tessellate_planned's output is a function of the surface and of what this header calls its
// TessellationKey — whether and how it was culled, the grid's steps, single or double precision of the grid's
// corners, the step count n_t of every trim segment (trimmed surfaces: they fix the trim polylines) and the
// planted defect (tests). Epsilon and the edge length reach the triangles only through those counts. Equal
// keys therefore give identical bytes, and reusing the buffer is the same as recomputing it; the tests hold
// both against each other along camera paths. A reused surface's SurfaceResult is the one its buffer was made
// with (its audit, run when the buffer was made, still describes these triangles); only `capped`, which can
// change while the steps sit at the cap, comes from this frame's plan.
//
// OWNERSHIP: a KeptTessellation belongs to one output buffer and is read and written only by whoever writes
// that buffer (one item of a frame, exactly once per frame). Keys are compared where they lie and rebuilt in
// place, so steady-state frames allocate nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::tess {

struct TessellationKey {
  Culled culled = Culled::no;
  StepSizes steps;
  bool single_precision = false;
  PlantedDefect planted_defect = PlantedDefect::none;
  std::vector<std::uint32_t> trim_steps;  // n_t of every trim segment, loop by loop (trimmed surfaces)
  friend bool operator==(const TessellationKey&, const TessellationKey&) = default;
};

// The key of `plan` for surface `s`, into `key` (its capacity kept).
inline void make_tessellation_key(const PreparedSurface& s, const SurfacePlan& plan,
                                  const TessellationSettings& settings, TessellationKey& key) {
  key.culled = plan.culled;
  key.trim_steps.clear();
  if (plan.culled != Culled::no) {
    key.steps = {};
    key.single_precision = false;
    key.planted_defect = PlantedDefect::none;
    return;
  }
  key.steps = plan.steps;
  key.planted_defect = settings.planted_defect;
  key.single_precision = plan.single_precision;
  for (const TrimSegmentShape& shape : s.segment_shapes) {
    key.trim_steps.push_back(static_cast<std::uint32_t>(
        trim_segment_steps(shape, s.bounds, plan.epsilon, plan.edge_length, settings.max_trim_steps)));
  }
}

// Whether `key` is what make_tessellation_key would make for `plan` (without building it: a reused surface, the
// common case, costs its plan and one n_t per trim segment).
inline bool tessellation_key_matches(const PreparedSurface& s, const SurfacePlan& plan,
                                     const TessellationSettings& settings, const TessellationKey& key) {
  if (key.culled != plan.culled) return false;
  if (plan.culled != Culled::no) return true;
  if (key.steps != plan.steps || key.planted_defect != settings.planted_defect ||
      key.single_precision != plan.single_precision) {
    return false;
  }
  if (key.trim_steps.size() != s.segment_shapes.size()) return false;
  for (std::size_t k = 0; k < s.segment_shapes.size(); ++k) {
    if (key.trim_steps[k] !=
        static_cast<std::uint32_t>(trim_segment_steps(s.segment_shapes[k], s.bounds, plan.epsilon, plan.edge_length,
                                                      settings.max_trim_steps))) {
      return false;
    }
  }
  return true;
}

// What a buffer was last made with.
struct KeptTessellation {
  bool valid = false;  // false: nothing kept (a new buffer, or forget())
  TessellationKey key;
  SurfaceResult result;
  void forget() noexcept { valid = false; }
};

struct ReuseOutcome {
  SurfaceResult result;
  bool remade = false;  // the surface was tessellated this time (false: its kept triangles were reused)
};

// tessellate_surface, except that a surface whose key equals the kept one keeps `out` as it is.
inline ReuseOutcome tessellate_or_reuse(const PreparedSurface& s, const Camera& camera, const Frustum& frustum,
                                        const TessellationSettings& settings, TessellationScratch& scratch,
                                        TriangleBuffers& out, KeptTessellation& kept) {
  PhaseLap lap(scratch.profile);
  const SurfacePlan plan = plan_surface(s, camera, frustum, settings);
  const bool same = kept.valid && tessellation_key_matches(s, plan, settings, kept.key);
  lap.to(plan.culled == Culled::no ? Phase::plan : Phase::cull);
  if (same) {
    SurfaceResult r = kept.result;
    r.capped = plan.capped;
    return {r, false};
  }
  kept.valid = false;  // until the buffer and the key agree again
  kept.result = tessellate_planned(s, plan, settings, scratch, out);
  make_tessellation_key(s, plan, settings, kept.key);  // in place: the kept key's capacity is reused
  kept.valid = true;
  return {kept.result, true};
}

}  // namespace frontsteal::tess
