// CGAL's constrained Delaunay triangulation of a §6 node set, as the
// independent reference for tests and benchmarks.
#pragma once

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <span>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"

namespace m4mesh::reference {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<NodeIndex, Kernel>;
using FaceBase = CGAL::Triangulation_face_base_with_info_2<bool, Kernel, CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

// Triangles inside the boundary polygon nodes[0 … boundary−1].
inline std::vector<Triangle> cgal_cdt(std::span<const Point> nodes, uint32_t boundary) {
  std::vector<std::pair<Kernel::Point_2, NodeIndex>> points;
  points.reserve(nodes.size());
  for (NodeIndex i = 0; i < nodes.size(); ++i) points.push_back({Kernel::Point_2(nodes[i].x, nodes[i].y), i});
  Cdt cdt;
  cdt.insert(points.begin(), points.end());
  std::vector<Cdt::Vertex_handle> handle(nodes.size());
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) handle[v->info()] = v;
  for (uint32_t i = 0; i < boundary; ++i) cdt.insert_constraint(handle[i], handle[(i + 1) % boundary]);

  // Outside: reachable from the infinite face without crossing a constraint.
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = false;
  std::vector<Cdt::Face_handle> stack{cdt.infinite_face()};
  cdt.infinite_face()->info() = true;
  while (!stack.empty()) {
    const Cdt::Face_handle f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle n = f->neighbor(i);
      if (!n->info() && !cdt.is_constrained(Cdt::Edge(f, i))) {
        n->info() = true;
        stack.push_back(n);
      }
    }
  }
  std::vector<Triangle> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (!f->info()) triangles.push_back(Triangle{{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}});
  return triangles;
}

}  // namespace m4mesh::reference
