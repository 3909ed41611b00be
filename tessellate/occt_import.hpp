// occt_import.hpp — STEP / IGES / BREP files into frontsteal's Model, through Open CASCADE (optional).
//
// Built only when CMake finds Open CASCADE (Debian: libocct-data-exchange-dev, libocct-modeling-algorithms-dev);
// then FRONTSTEAL_HAVE_OCCT is ON and the library frontsteal_occt_import provides this function.
//
// Per face of the file's shape (each distinct face once, in TopExp::MapShapes order, numbered from 0):
//   1. BRepBuilderAPI_NurbsConvert turns analytic faces (planes, cylinders, cones, spheres, tori, revolved and
//      extruded surfaces) into B-spline faces. Every degree Open CASCADE allows (up to 25, kMaxDegree) is kept
//      as it is: no face is approximated or skipped for its degree.
//   2. Trim loops: each wire of the face taken FORWARD is walked with BRepTools_WireExplorer; every edge's
//      p-curve (BRep_Tool::CurveOnSurface, which picks the right one of a seam edge's two by the edge's
//      orientation) is sampled to a polyline in the face's (u, v) — `samples_per_span` segments per knot span,
//      one per span of a straight (degree-1) p-curve — backwards for a REVERSED edge; degenerate edges (at a
//      pole) are kept, for they close the loop in (u, v); consecutive duplicates are dropped. A gap between
//      consecutive p-curves up to 1% of the face's (u, v) extent is bridged by a straight segment; a larger
//      one skips the face (the wire is not closed in (u, v)). Loops are then oriented by nesting (a loop
//      inside an even number of others is an outer boundary, counter-clockwise; otherwise a hole, clockwise):
//      a loop found the wrong way round is reversed and counted in `loops_reoriented`; a loop enclosing no
//      area is dropped (and reported).
//   3. The B-spline is cut to the loops' (u, v) range (Geom_BSplineSurface::Segment, which also unrolls a
//      periodic direction; the loops are shifted by whole periods when Segment moved the range) and split at
//      its knots into rational Bézier patches (GeomConvert_BSplineSurfaceToBezierSurface); the knots are the
//      patch grid. Loop points are clamped into the grid's range and put exactly on a grid line when within
//      10⁻⁵ of a cell of it (split_region nudges points lying on a line by 10⁻⁶ of a cell; a point left just
//      beside the line could otherwise cross its nudged neighbours). Where consecutive p-curves overshoot each
//      other at a corner, the tiny loop this makes is cut off (`corner_loops_cut`).
//   4. The material region is split along that grid by split_region (trim_region.hpp). A full cell becomes an
//      untrimmed Surface, each piece of a partial cell a Surface whose loops (outer, then holes) are polylines
//      mapped affinely from the cell to [0,1]² (clamped into it); an empty cell gives nothing.
//   5. A face REVERSED in the shape gets its patches mirrored in u (control row i → m−i; loops u → 1−u with the
//      point order reversed), so S_u × S_v points the face's way (outwards on a solid).
//   6. Every Surface is written and parsed back through the native format's strict checks; one that fails is
//      left out and the reason reported.
// Surfaces are named "<file stem>_f<face>_p<patch>" (patch = iu·nv + iv in the face's grid), with "_<k>"
// added when a cell has several pieces; <file stem> is also the model's name when `out` had none. Faces of a
// closed shell of a solid are marked `solid` (their normals point outwards). Components are not assigned (-1).
#pragma once

#include <string>
#include <vector>

#include "tessellate/model.hpp"

namespace frontsteal::tess {

struct ImportSkip {
  int face;            // face number in the file (0-based)
  std::string reason;  // what was left out (a face, a loop, a piece) and why
};

struct ImportReport {
  std::string file;
  int faces = 0;             // distinct faces in the file's shape
  int faces_imported = 0;    // faces that gave at least one Surface
  int patches = 0;           // Bézier patches of the faces that were converted (every cell of their knot grids)
  int surfaces = 0;          // Surfaces appended to the model
  int trim_loops = 0;        // closed (u, v) loops built from the wires of converted faces
  int loops_reoriented = 0;  // loops found the wrong way round for their nesting and reversed
  int corner_loops_cut = 0;  // loops where p-curves overshooting each other at a corner made a tiny loop, cut off
  // The largest distance between a Bézier patch as imported (evaluated by bezier_patch.hpp) and Open CASCADE's
  // own B-spline surface (Geom_Surface::D0) at the same parameters, over a 5×5 grid of every patch; in model
  // units. It measures the conversion (knot splitting, the homogeneous form, rounding), checked by an
  // evaluator that is not ours.
  double max_patch_error = 0;
  std::vector<ImportSkip> skipped;
  // Whole-file doubts that are not errors: a STEP file without its END-ISO-10303-21 trailer or an IGES file
  // without its terminate section was probably cut short, so "43 of 213 faces" may be all that was read.
  std::vector<std::string> warnings;
};

struct ImportOptions {
  int samples_per_span = 8;  // p-curve sampling: segments per knot span (>= 1)
  // Tests only: every patch's middle control point (or the one after the middle) moved by a thousandth of the
  // patch's extent before max_patch_error is measured, as a wrong knot split or weight conversion would.
  bool planted_patch_shift = false;
};

// Reads a .step/.stp/.iges/.igs/.brep file (chosen by extension, case-insensitive) and appends its faces to
// `out` as trimmed Bézier surfaces. Throws std::runtime_error naming the file for an unknown extension, a file
// that cannot be opened, or one Open CASCADE cannot read or that holds no shape (then `out` is unchanged);
// std::invalid_argument for samples_per_span < 1. Problems with single faces are not errors: they are skipped
// and listed in the report. Not thread-safe: while it runs, Open CASCADE's default messenger is silenced (its
// printers are swapped out and put back), so call it from one thread at a time.
ImportReport import_cad_file(const std::string& path, Model& out, const ImportOptions& options = {});

}  // namespace frontsteal::tess
