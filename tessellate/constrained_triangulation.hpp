// constrained_triangulation.hpp — triangulating a large piece of a trimmed cell without ear clipping's n².
//
// Ear clipping (polygon_triangulation.hpp) is quadratic in the piece's size: right for the small pieces of a
// fine grid, wrong for a piece that holds a long trim polyline (a coarse grid on a densely trimmed CAD face:
// thousands of trim points in one cell). Such a piece goes to a constrained triangulation (CGAL's
// Constrained_triangulation_2, exact predicates): every ring vertex inserted in a spatial order, every ring
// edge a constraint, and the faces inside the piece picked by nesting depth — a face reached from outside by
// crossing an odd number of constraints is inside. Not the Delaunay one: its in-circle tests fall back to exact
// arithmetic on the nearly co-circular points of circular trims and cost twice the time, and the triangles
// need no quality ear clipping's do not have either. Measured (piece_triangulation_benchmark, a smooth closed
// curve with a hole): 0.23 µs per vertex at 1,024 vertices, 0.37 at 4,096, against ear clipping's 0.8 and 3.0.
// Holes need no bridges, and a hole touching the outer ring or another hole at a shared vertex is no special
// case: the flood fill only crosses edges.
//
// The result is used only if it is a triangulation of the piece on its own vertices, which the function
// checks: no two ring vertices of different ids at the same (u, v), no constraint crossing another (that
// would need a new vertex, which has no id), and every ring edge an edge of the triangulation (a ring vertex
// lying on another ring's edge splits that edge, and the tiling audit, which counts edges by id, would not
// find it). Otherwise it returns false, appends nothing, and the caller triangulates by ear clipping. Either
// way the caller's tiling audit (tiling_audit.hpp) checks the triangles it gets; it does not trust this file.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "tessellate/polygon_triangulation.hpp"

namespace frontsteal::tess {

// Pieces with at least this many ring vertices (outer and holes together) are triangulated here; below it,
// ear clipping is faster (no allocation; piece_triangulation_benchmark: the two cross between 256 and 512
// vertices) and its triangles are the frame's reference bytes (no piece of the plant scenes is this large).
inline constexpr std::size_t kConstrainedTriangulationMinVertices = 384;

// Appends the piece's triangles as counter-clockwise id triples to `triangles` and returns true; or returns
// false and leaves `triangles` as it was (see above). `outer` is counter-clockwise, `holes` clockwise.
bool triangulate_constrained(const PolygonRing& outer, std::span<const PolygonRing> holes,
                             std::vector<std::uint32_t>& triangles);

}  // namespace frontsteal::tess
