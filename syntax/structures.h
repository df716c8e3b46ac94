// The syntax structures of §3, holding element values exactly as coded.
#pragma once

#include <cstdint>
#include <vector>

namespace m4mesh {

inline constexpr uint32_t kMeshTypeUniform = 0;
inline constexpr uint32_t kMeshTypeDelaunay = 1;

struct UniformGeometry {
  uint32_t nr_of_mesh_nodes_hori = 0;
  uint32_t nr_of_mesh_nodes_verti = 0;
  uint32_t mesh_rect_size_hori = 0;
  uint32_t mesh_rect_size_verti = 0;
  uint32_t triangle_split_code = 0;
};

// One coded coordinate difference: the VLC length L and its L bits.
struct DeltaCode {
  int length = 0;
  uint32_t bits = 0;
};

struct NodeDelta {
  DeltaCode x;
  DeltaCode y;
};

struct DelaunayGeometry {
  uint32_t nr_of_mesh_nodes = 0;
  uint32_t nr_of_boundary_nodes = 0;
  uint32_t node0_x = 0;
  uint32_t node0_y = 0;
  std::vector<NodeDelta> deltas;  // nodes 1 … nr_of_mesh_nodes−1
};

struct MeshGeometry {
  uint32_t mesh_type_code = kMeshTypeUniform;
  UniformGeometry uniform;
  DelaunayGeometry delaunay;
};

// One node of MeshMotion, in traversal order. 16-bit fields: a store to an
// 8-bit one may alias any object, so the reader's state could not stay in
// registers while a P-plane is read.
struct NodeMotion {
  uint16_t node_motion_vector_flag = 0;
  int16_t delta_mv_x = 0;  // VLC value m, −32 … 32
  uint16_t delta_mv_x_res = 0;
  int16_t delta_mv_y = 0;
  uint16_t delta_mv_y_res = 0;
};

struct MeshMotion {
  uint32_t motion_range_code = 1;
  std::vector<NodeMotion> nodes;
};

struct MeshObjectPlane {
  uint32_t new_mesh_flag = 1;
  MeshGeometry geometry;  // when new_mesh_flag == 1
  MeshMotion motion;      // when new_mesh_flag == 0
};

struct MeshObject {
  std::vector<MeshObjectPlane> planes;
  bool has_end_code = true;
};

// nr_of_mesh_nodes of an I-plane (§3.1 for uniform meshes).
uint32_t node_count(const MeshGeometry& geometry);

}  // namespace m4mesh
