#include "mesh/uniform.h"

namespace m4mesh {

std::vector<Point> uniform_nodes(const UniformParams& p) {
  std::vector<Point> nodes;
  nodes.reserve(size_t{p.cols} * p.rows);
  for (uint32_t r = 0; r < p.rows; ++r)
    for (uint32_t c = 0; c < p.cols; ++c)
      nodes.push_back(Point{static_cast<int32_t>(c * p.dx), static_cast<int32_t>(r * p.dy)});
  return nodes;
}

bool uniform_split_tl_br(uint32_t split, uint32_t c, uint32_t r) {
  switch (split) {
    case 0: return true;
    case 1: return false;
    case 2: return (c + r) % 2 == 0;
    default: return (c + r) % 2 == 1;
  }
}

std::vector<Triangle> uniform_triangles(const UniformParams& p) {
  std::vector<Triangle> triangles;
  triangles.reserve(size_t{2} * (p.cols - 1) * (p.rows - 1));
  for (uint32_t r = 0; r + 1 < p.rows; ++r) {
    for (uint32_t c = 0; c + 1 < p.cols; ++c) {
      const NodeIndex tl = r * p.cols + c, tr = tl + 1, bl = tl + p.cols, br = bl + 1;
      if (uniform_split_tl_br(p.split, c, r)) {
        triangles.push_back({{tl, tr, br}});
        triangles.push_back({{tl, br, bl}});
      } else {
        triangles.push_back({{tl, tr, bl}});
        triangles.push_back({{tr, br, bl}});
      }
    }
  }
  return triangles;
}

MeshTopology uniform_topology(const UniformParams& params) {
  MeshTopology mesh{uniform_triangles(params), {}};
  mesh.neighbours = triangle_neighbours(mesh.triangles, size_t{params.cols} * params.rows);
  return mesh;
}

}  // namespace m4mesh
