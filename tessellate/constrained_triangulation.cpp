// constrained_triangulation.cpp — the constrained triangulation of a large piece (see the header).
// CGAL stays behind this file: no other translation unit pays for its headers.
#include "tessellate/constrained_triangulation.hpp"

#include <CGAL/Constrained_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/property_map.h>
#include <CGAL/spatial_sort.h>
#include <utility>

namespace frontsteal::tess {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
// A face's nesting depth: how many constraints a path from the infinite face crosses to reach it (−1 unvisited).
using FaceBase =
    CGAL::Triangulation_face_base_with_info_2<int, Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Any intersection between constraints, even at an existing vertex, throws: the piece would not be triangulated
// on its own ring edges, which is what the caller's audit counts.
using Triangulation = CGAL::Constrained_triangulation_2<Kernel, DataStructure, CGAL::No_constraint_intersection_tag>;
using VertexHandle = Triangulation::Vertex_handle;
using FaceHandle = Triangulation::Face_handle;

// Flood fill by depth: the faces reachable from `seed` without crossing a constraint get `depth`; faces across a
// constraint from them are queued for depth + 1.
void fill_depths(Triangulation& cdt) {
  for (const FaceHandle f : cdt.all_face_handles()) f->info() = -1;
  std::vector<FaceHandle> frontier{cdt.infinite_face()}, next_frontier, stack;
  for (int depth = 0; !frontier.empty(); ++depth) {
    next_frontier.clear();
    for (const FaceHandle seed : frontier) {
      if (seed->info() != -1) continue;
      seed->info() = depth;
      stack.assign(1, seed);
      while (!stack.empty()) {
        const FaceHandle f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
          const FaceHandle n = f->neighbor(i);
          if (n->info() != -1) continue;
          if (cdt.is_constrained(Triangulation::Edge(f, i))) {
            next_frontier.push_back(n);
          } else {
            n->info() = depth;
            stack.push_back(n);
          }
        }
      }
    }
    frontier.swap(next_frontier);
  }
}

}  // namespace

bool triangulate_constrained(const PolygonRing& outer, std::span<const PolygonRing> holes,
                             std::vector<std::uint32_t>& triangles) {
  // Every ring's vertices, inserted in a spatial (Hilbert) order: a trim polyline's points lie along a curve,
  // and inserted in ring order each new point would flip a fan of edges across the whole curve (quadratic).
  std::vector<const PolygonRing*> rings;
  if (outer.size() >= 3) rings.push_back(&outer);  // a ring of fewer than three vertices bounds nothing
  for (const PolygonRing& hole : holes) {
    if (hole.size() >= 3) rings.push_back(&hole);
  }
  std::vector<Kernel::Point_2> points;
  std::vector<std::uint32_t> ids;
  for (const PolygonRing* ring : rings) {
    for (const PolygonVertex& p : *ring) {
      points.emplace_back(p.uv.x, p.uv.y);
      ids.push_back(p.id);
    }
  }
  std::vector<std::size_t> order(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  using SortTraits = CGAL::Spatial_sort_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Kernel::Point_2>::type>;
  CGAL::spatial_sort(order.begin(), order.end(), SortTraits(CGAL::make_property_map(points)));

  Triangulation cdt;
  std::vector<VertexHandle> vertex_of(points.size());
  FaceHandle hint;
  for (const std::size_t k : order) {
    const std::size_t before = cdt.number_of_vertices();
    const VertexHandle v = cdt.insert(points[k], hint);
    if (cdt.number_of_vertices() != before) {
      v->info() = ids[k];
    } else if (v->info() != ids[k]) {
      return false;  // two ids at one (u, v): one of them would have no triangle
    }
    vertex_of[k] = v;
    hint = v->face();
  }
  std::vector<std::pair<VertexHandle, VertexHandle>> ring_edges;
  try {
    std::size_t first = 0;
    for (const PolygonRing* ring : rings) {
      for (std::size_t k = 0; k < ring->size(); ++k) {
        const VertexHandle a = vertex_of[first + k], b = vertex_of[first + (k + 1) % ring->size()];
        if (a == b) continue;
        cdt.insert_constraint(a, b);
        ring_edges.emplace_back(a, b);
      }
      first += ring->size();
    }
  } catch (const Triangulation::Intersection_of_constraints_exception&) {
    return false;
  }
  if (cdt.dimension() < 2) return false;  // collinear: no face; ear clipping emits the degenerate triangles
  // Every ring edge must be an edge of the triangulation (see the header).
  for (const auto& [a, b] : ring_edges) {
    FaceHandle f;
    int i = 0;
    if (!cdt.is_edge(a, b, f, i)) return false;
  }
  fill_depths(cdt);
  for (const FaceHandle f : cdt.finite_face_handles()) {
    if (f->info() % 2 == 0) continue;  // outside the piece, or in a hole
    triangles.insert(triangles.end(), {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  return true;
}

}  // namespace frontsteal::tess
