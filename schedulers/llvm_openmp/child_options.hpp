// child_options.hpp — frontsteal-llvm-openmp's options (the main job passes them; tests add the negative
// controls --schedule and --fault), parsed by report::CommandLine (CLI11, compiled by clang here too): usage
// errors exit 2 naming the flag, --help prints the options.
#pragma once

#include <string>

#include "tessellate/camera_path.hpp"
#include "tessellate/surface_tessellator.hpp"

namespace frontsteal::llvm_openmp {

namespace ts = frontsteal::tess;

inline constexpr const char* kProgram = "frontsteal-llvm-openmp";

struct Options {
  int workers = 0;
  std::string scene = "plant:15906";
  int frames = 24;
  ts::CameraPathKind path = ts::CameraPathKind::orbit_then_zoom;
  double tolerance = 1.0;
  int width = 1280, height = 720;
  int grain = 1;
  ts::PlantedDefect defect = ts::PlantedDefect::none;
  bool pin = false;
  bool reuse = false;                     // frame-to-frame reuse (tessellate/surface_reuse.hpp), as frontsteal --reuse
  std::string schedule = "static-steal";  // static-steal | monotonic-dynamic | static (negative controls)
  enum class Fault { none, drop, dup } fault = Fault::none;
  int fault_item = -1;
};

Options parse_options(int argc, char** argv);

}  // namespace frontsteal::llvm_openmp
