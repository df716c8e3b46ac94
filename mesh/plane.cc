#include "mesh/plane.h"

namespace m4mesh {

MeshPlane uniform_plane(uint32_t cols, uint32_t rows, uint32_t dx, uint32_t dy, uint32_t split) {
  MeshPlane plane;
  plane.info.kind = MeshKind::kUniform;
  plane.info.uniform = UniformParams{cols, rows, dx, dy, split};
  plane.nodes = uniform_nodes(plane.info.uniform);
  return plane;
}

MeshPlane delaunay_plane(std::vector<Point> nodes, uint32_t boundary) {
  MeshPlane plane;
  plane.info.kind = MeshKind::kDelaunay;
  plane.info.boundary = boundary;
  plane.nodes = std::move(nodes);
  return plane;
}

MeshPlane inter_plane(std::vector<Point> nodes, uint32_t range) {
  MeshPlane plane;
  plane.info.intra = false;
  plane.info.range = range;
  plane.nodes = std::move(nodes);
  return plane;
}

}  // namespace m4mesh
