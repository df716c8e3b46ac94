#include "mesh/traversal.h"

#include "common/error.h"

namespace m4mesh {

namespace {

struct QueuedTriangle {
  NodeIndex l, m, n;
  uint32_t triangle;
};

Error traversal_error(const std::string& message) {
  return Error(ErrorKind::kGeometry, "", kNoPlane, kNoOffset, message);
}

}  // namespace

MotionOrder method2_order(std::span<const Triangle> triangles, const TriangleNeighbours& neighbours,
                          size_t node_count, NodeIndex first, NodeIndex second) {
  MotionOrder order;
  order.zero_slot = static_cast<NodeIndex>(node_count);
  order.node.reserve(node_count);
  order.pred_a.reserve(node_count);
  order.pred_b.reserve(node_count);
  std::vector<uint8_t> done(node_count, 0);
  auto code = [&](NodeIndex node, NodeIndex a, NodeIndex b) {
    order.node.push_back(node);
    order.pred_a.push_back(a);
    order.pred_b.push_back(b);
    done[node] = 1;
  };

  uint32_t start = kNoTriangle;
  for (uint32_t t = 0; t < triangles.size() && start == kNoTriangle; ++t)
    for (int j = 0; j < 3; ++j)
      if (triangles[t].v[j] == first && triangles[t].v[(j + 1) % 3] == second) start = t;
  if (start == kNoTriangle)
    throw traversal_error("no clockwise triangle holds the initial edge " + std::to_string(first) + "→" +
                          std::to_string(second));
  code(first, order.zero_slot, order.zero_slot);
  code(second, first, first);

  std::vector<uint8_t> labelled(triangles.size(), 0);
  std::vector<QueuedTriangle> queue;  // FIFO: a vector read from the front
  queue.reserve(triangles.size());
  labelled[start] = 1;
  queue.push_back({first, second, triangles[start].v[(triangles[start].corner_of(second) + 1) % 3], start});
  // The neighbour of t across the edge (a, b) opposite `across`, with its far node.
  auto enqueue = [&](uint32_t t, NodeIndex across, NodeIndex base0, NodeIndex base1) {
    const uint32_t next = neighbours[t][triangles[t].corner_of(across)];
    if (next == kNoTriangle || labelled[next]) return;
    labelled[next] = 1;
    queue.push_back({base0, base1, triangles[next].third(base0, base1), next});
  };
  for (size_t head = 0; head < queue.size(); ++head) {
    const QueuedTriangle t = queue[head];
    if (!done[t.n]) code(t.n, t.l, t.m);
    enqueue(t.triangle, t.m, t.l, t.n);  // right edge (l, n), appended as ⟨l, n, q⟩
    enqueue(t.triangle, t.l, t.n, t.m);  // left edge (m, n), appended as ⟨n, m, q⟩
  }
  if (order.node.size() != node_count) {
    for (NodeIndex i = 0; i < node_count; ++i)
      if (!done[i]) throw traversal_error("node " + std::to_string(i) + " is not reached by the traversal");
  }
  return order;
}

MotionOrder method1_order(std::span<const NodeIndex> sequence) {
  MotionOrder order;
  order.zero_slot = static_cast<NodeIndex>(sequence.size());
  NodeIndex previous = order.zero_slot;
  for (NodeIndex node : sequence) {
    order.node.push_back(node);
    order.pred_a.push_back(previous);
    order.pred_b.push_back(previous);
    previous = node;
  }
  return order;
}

std::vector<NodeIndex> boustrophedon(uint32_t cols, uint32_t rows) {
  std::vector<NodeIndex> sequence;
  sequence.reserve(size_t{cols} * rows);
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t i = 0; i < cols; ++i) sequence.push_back(r * cols + (r % 2 == 0 ? i : cols - 1 - i));
  return sequence;
}

MotionOrder plane_motion_order(MotionMethod method, const MeshTopology& mesh, size_t node_count, const UniformParams* uniform,
                               uint32_t boundary) {
  if (method == MotionMethod::kMethod2) return method2_order(mesh.triangles, mesh.neighbours, node_count, 0, uniform ? 1 : boundary - 1);
  if (uniform) return method1_order(boustrophedon(uniform->cols, uniform->rows));
  std::vector<NodeIndex> sequence(node_count);
  for (size_t i = 0; i < node_count; ++i) sequence[i] = static_cast<NodeIndex>(i);
  return method1_order(sequence);
}

}  // namespace m4mesh
