// Uniform meshes (§5).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"

namespace m4mesh {

struct UniformParams {
  uint32_t cols = 0;   // nr_of_mesh_nodes_hori
  uint32_t rows = 0;   // nr_of_mesh_nodes_verti
  uint32_t dx = 0;     // mesh_rect_size_hori
  uint32_t dy = 0;     // mesh_rect_size_verti
  uint32_t split = 0;  // triangle_split_code
  friend bool operator==(const UniformParams&, const UniformParams&) = default;
};

// Node (c, r) has index r·cols + c and lies at (c·dx, r·dy).
std::vector<Point> uniform_nodes(const UniformParams& params);
// Two clockwise triangles per rectangle, rectangles in row-major order.
std::vector<Triangle> uniform_triangles(const UniformParams& params);
// The triangles with their adjacency.
MeshTopology uniform_topology(const UniformParams& params);
// Whether rectangle (c, r) is split top-left to bottom-right.
bool uniform_split_tl_br(uint32_t split, uint32_t c, uint32_t r);

}  // namespace m4mesh
