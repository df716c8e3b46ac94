// A decoded (or to-be-encoded) mesh object plane: what §9 prints.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"
#include "mesh/uniform.h"

namespace m4mesh {

enum class MeshKind { kUniform, kDelaunay };

struct PlaneInfo {
  bool intra = true;
  MeshKind kind = MeshKind::kUniform;  // I-planes
  UniformParams uniform;               // uniform I-planes
  uint32_t boundary = 0;               // Delaunay I-planes: nr_of_boundary_nodes
  uint32_t range = 0;                  // P-planes: motion_range_code (0 = let the encoder choose)
  friend bool operator==(const PlaneInfo&, const PlaneInfo&) = default;
};

struct MeshPlane {
  PlaneInfo info;
  std::vector<Point> nodes;         // positions after this plane, by node index
  std::vector<Triangle> triangles;  // I-planes
};

// A uniform I-plane on its grid, a Delaunay I-plane (boundary nodes first),
// and a P-plane (range 0: the encoder chooses).
MeshPlane uniform_plane(uint32_t cols, uint32_t rows, uint32_t dx, uint32_t dy, uint32_t split);
MeshPlane delaunay_plane(std::vector<Point> nodes, uint32_t boundary);
MeshPlane inter_plane(std::vector<Point> nodes, uint32_t range = 0);

}  // namespace m4mesh
