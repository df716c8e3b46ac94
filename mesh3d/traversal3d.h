// The breadth-first traversal of the patent's Method II on a 3D triangle
// mesh (docs/codec_bfs3d.md): any orientable mesh, with boundaries, several
// components and isolated vertices.
#pragma once

#include <span>
#include <vector>

#include "mesh/topology.h"

namespace m4mesh {

// Coding order of the vertices; the k-th is predicted from pred_a[k] and
// pred_b[k] (average), or with the parallelogram pred_a + pred_b − pred_c
// when pred_c is not zero_slot. zero_slot stands for a zero vector.
struct MotionOrder3d {
  std::vector<NodeIndex> node;
  std::vector<NodeIndex> pred_a, pred_b, pred_c;
  NodeIndex zero_slot = 0;
};

// Start rule: components are started in face order, each at the first face
// not yet reached, whose listed corners v0, v1, v2 give the base edge
// (v0, v1). Vertices in no face come last, in index order, predicted from zero.
MotionOrder3d bfs3d_order(std::span<const Triangle> faces, size_t vertex_count);

}  // namespace m4mesh
