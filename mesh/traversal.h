// The order in which a P-plane codes its node motion vectors, with the two
// predictor nodes of each (§7, §8). Computed once per I-plane, so that a
// P-plane decodes in one linear pass: the prediction of the k-th coded node
// is ((v[pred_a[k]] + v[pred_b[k]] + 1) >> 1), where the index zero_slot
// stands for a vector that is always (0, 0).
#pragma once

#include <span>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"
#include "mesh/uniform.h"

namespace m4mesh {

// Method II is the normative one; Method I is not signalled (§8) and must be
// chosen on both sides.
enum class MotionMethod { kMethod2, kMethod1 };

struct MotionOrder {
  std::vector<NodeIndex> node;
  std::vector<NodeIndex> pred_a;
  std::vector<NodeIndex> pred_b;
  NodeIndex zero_slot = 0;  // == node count
};

// Method II (§7): breadth-first over the clockwise triangles, starting at the
// triangle holding the directed edge first → second. Fails (kGeometry) when
// that edge is missing or a node is in no triangle reached.
MotionOrder method2_order(std::span<const Triangle> triangles, const TriangleNeighbours& neighbours,
                          size_t node_count, NodeIndex first, NodeIndex second);

// Method I (§8): each node predicted from the one before it in `sequence`.
MotionOrder method1_order(std::span<const NodeIndex> sequence);
// §8's uniform order: row 0 left to right, row 1 right to left, …
std::vector<NodeIndex> boustrophedon(uint32_t cols, uint32_t rows);

// The order of the P-planes after an I-plane, one rule for the encoder and
// the decoder. Method II starts at the top-left node 0 and the next
// clockwise boundary node (§7.1): node 1 of a uniform mesh (`uniform`
// given), node boundary − 1 of a Delaunay one. Method I follows the
// boustrophedon of a uniform mesh, the node order of a Delaunay one.
MotionOrder plane_motion_order(MotionMethod method, const MeshTopology& mesh, size_t node_count, const UniformParams* uniform,
                               uint32_t boundary);

// The prediction of the k-th coded node's vector (§7.2, §8).
inline Point predicted_vector(const MotionOrder& order, size_t k, const Point* vectors) {
  const Point& a = vectors[order.pred_a[k]];
  const Point& b = vectors[order.pred_b[k]];
  return {(a.x + b.x + 1) >> 1, (a.y + b.y + 1) >> 1};
}

}  // namespace m4mesh
