#!/usr/bin/env bash
# bootstrap.sh — installs every Debian package frontsteal needs, and nothing else.
#
# Idempotent: packages already present are left alone (apt-get install is a no-op for them), and the
# apt-get update step is skipped when every package is already installed, so the README's commands stay
# fast on a machine that has run them before. Needs root (or sudo) on Debian 12.
set -euo pipefail

packages=(
  # build
  g++ cmake ninja-build make pkg-config
  # tests and benchmarks
  catch2 libbenchmark-dev
  # model checking (models_check/): Relacy, header-only
  relacy-dev
  # model checking (models_check/spin/): SPIN, the second engine (pan is compiled with gcc at test time)
  spin
  # ThreadSanitizer runtime for g++ 12 (stress/)
  libtsan2
  # vector and matrix math for the tessellation workload (tessellate/), and CGAL's constrained triangulation
  # for its large trimmed pieces (tessellate/constrained_triangulation.cpp; header-only, brings GMP and MPFR)
  libglm-dev libcgal-dev
  # the GLU NURBS tessellator: the reference in tessellate/benchmarks/glu_reference_benchmark
  libglu1-mesa-dev
  # the parser's fuzz target (tessellate/fuzz/, `cmake --workflow --preset fuzz`)
  clang-14 libclang-rt-14-dev
  # the formatting check (.clang-format, ctest format.*) and the static checks (.clang-tidy, ctest tidy.*)
  clang-format-14 clang-tidy-14
  # the CAD importer frontsteal-import (tessellate/occt_import.cpp): Open CASCADE 7.6 (OCCT's CMake targets
  # also name libtbb.so), and the real STEP/IGES/BREP files its test reads (never committed)
  libocct-data-exchange-dev libocct-modeling-algorithms-dev libtbb-dev
  occt-misc calculix-cgx-examples gmsh-doc
  # every executable's options (CLI11) and results files (nlohmann-json): reporting/
  libcli11-dev nlohmann-json3-dev
  # the main job's plots (schedulers/main_job/frontsteal_main.cpp writes a gnuplot script and runs it); oneTBB is
  # listed above (libtbb-dev), OpenMP comes with g++ (libgomp)
  gnuplot-nox
  # the end-to-end tests read the main job's JSON files (tests/schedulers/main_job/frontsteal_calibrate_test.sh)
  python3
  # the lock-free global queue peer, moodycamel-queue (schedulers/concurrent_queue_scheduler.hpp): header-only
  libconcurrentqueue-dev
  # openmp-static-steal: LLVM's OpenMP runtime (static_steal), in its own executable built with clang++-14
  # (listed above) so that libomp and libgomp never share a process (schedulers/llvm_openmp/)
  libomp-14-dev
  # greedy rendering (render/): headless OpenGL through EGL (Mesa's llvmpipe without a GPU), PNG output
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev
  # the interactive viewer frontsteal-view (render/view_main.cpp): GLFW windows, Dear ImGui (Debian's libimgui.a
  # holds the glfw and opengl3 backends; its font atlas needs stb's library)
  libglfw3-dev libimgui-dev libstb-dev
  # its test under a virtual X server (tests/render/view_xvfb_test.sh): Xvfb, xdotool for the input, Xlib for
  # the WM_DELETE_WINDOW sender (tests/render/x11_close_window.cpp)
  xvfb xdotool libx11-dev
  # the distributed layer (distributed/, frontsteal-mpi and its ctest entries): Open MPI 4.1 (mpirun, mpicxx,
  # MPI-3 one-sided communication). Optional at configure time; with MPICH instead, swap these two names for
  # mpich libmpich-dev
  openmpi-bin libopenmpi-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "bootstrap: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "bootstrap: done"
