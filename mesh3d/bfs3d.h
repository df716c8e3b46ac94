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

// The predicted motion of the k-th coded vertex, per axis, from the
// motion of the vertices coded before it: the average of its base edge's
// ends (a, b), or with `parallelogram` and a vertex c across that edge,
// a + b − c.
inline std::array<int64_t, 3> predict_motion(const MotionOrder3d& order, size_t k, std::span<const std::array<int32_t, 3>> motion,
                                             bool parallelogram) {
  const std::array<int32_t, 3>& a = motion[order.pred_a[k]];
  const std::array<int32_t, 3>& b = motion[order.pred_b[k]];
  std::array<int64_t, 3> predicted;
  if (parallelogram && order.pred_c[k] != order.zero_slot) {
    const std::array<int32_t, 3>& c = motion[order.pred_c[k]];
    for (int axis = 0; axis < 3; ++axis) predicted[axis] = int64_t{a[axis]} + b[axis] - c[axis];
  } else {
    for (int axis = 0; axis < 3; ++axis) predicted[axis] = (int64_t{a[axis]} + b[axis] + 1) >> 1;
  }
  return predicted;
}

}  // namespace m4mesh
