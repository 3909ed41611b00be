// model_parser_fuzz — libFuzzer target for the native model format's strict parser (clang-14 with Debian's
// libclang-rt-14-dev; build with `cmake --workflow --preset fuzz`, see docs/tessellation.md).
//
// Properties checked on every input:
//   1. parse_model either returns a model or throws ModelError — any other exception, crash, leak or
//      undefined behaviour (ASan + UBSan are on) is a finding;
//   2. an accepted model survives write_model → parse_model with the same surfaces;
//   3. an accepted model tessellates (a fixed camera, small step caps) with every triangle index in range and
//      without any inconsistency of the per-surface audit (tracing, tiling, area: surface_tessellator.hpp,
//      step 6) — an accepted model the tessellator cannot tile exactly is a parser (or tessellator) finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "tessellate/model_format.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace ts = frontsteal::tess;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  ts::Model model;
  try {
    model = ts::parse_model(in, "fuzz");
  } catch (const ts::ModelError&) {
    return 0;  // rejected with a file:line reason: the expected outcome for most inputs
  }
  std::ostringstream out;
  ts::write_model(out, model);
  std::istringstream again(out.str());
  const ts::Model back = ts::parse_model(again, "fuzz-roundtrip");  // must not throw
  if (back.surfaces.size() != model.surfaces.size()) std::abort();

  ts::Camera cam;
  cam.eye = {2.0, -3.0, 2.5};
  cam.target = {0.0, 0.0, 0.0};
  ts::TessellationSettings settings;
  settings.max_steps = 16;
  settings.max_trim_steps = 16;
  settings.frustum_culling = false;
  ts::TessellationScratch scratch;
  ts::TriangleBuffers tri;
  for (const ts::Surface& s : model.surfaces) {
    const ts::SurfaceResult r =
        ts::tessellate_surface(ts::prepare_surface(s), cam, ts::Frustum::of(cam), settings, scratch, tri);
    if (r.inconsistencies() > 0) std::abort();
    for (std::uint32_t index : tri.indices) {
      if (index >= tri.positions.size()) std::abort();
    }
  }
  return 0;
}
