#include "syntax/structures.h"

namespace m4mesh {

uint32_t node_count(const MeshGeometry& geometry) {
  if (geometry.mesh_type_code == kMeshTypeUniform)
    return geometry.uniform.nr_of_mesh_nodes_hori * geometry.uniform.nr_of_mesh_nodes_verti;
  return geometry.delaunay.nr_of_mesh_nodes;
}

}  // namespace m4mesh
