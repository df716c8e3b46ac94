// The normative process of bfs3d (codec_id 1) shared by its encoder and
// decoder (docs/codec_bfs3d.md): the breadth-first traversal of the
// patent's Method II on a 3D triangle mesh (any orientable mesh, with
// boundaries, several components and isolated vertices) and the motion
// prediction along it.
#pragma once

#include <array>
#include <cstdint>
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

// The predicted motion of the k-th coded vertex on one axis from the motion
// of the vertices coded before it: the average of its base edge's ends
// (a, b), or with `parallelogram` and a vertex c across that edge, a + b − c.
inline int64_t predict_motion(const MotionOrder3d& order, size_t k, std::span<const std::array<int32_t, 3>> motion, int axis,
                              bool parallelogram) {
  const int64_t a = motion[order.pred_a[k]][axis], b = motion[order.pred_b[k]][axis];
  if (parallelogram && order.pred_c[k] != order.zero_slot) return a + b - motion[order.pred_c[k]][axis];
  return (a + b + 1) >> 1;
}

}  // namespace m4mesh
