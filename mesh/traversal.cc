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

MotionOrder method2_order(std::span<const Triangle> triangles, size_t node_count, NodeIndex first,
                          NodeIndex second) {
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

  HalfEdges edges(triangles, node_count);
  HalfEdges::Found start;
  if (!edges.find(first, second, start))
    throw traversal_error("no clockwise triangle holds the initial edge " + std::to_string(first) + "→" +
                          std::to_string(second));
  code(first, order.zero_slot, order.zero_slot);
  code(second, first, first);

  std::vector<uint8_t> labelled(triangles.size(), 0);
  std::vector<QueuedTriangle> queue;  // FIFO: a vector read from the front
  queue.reserve(triangles.size());
  labelled[start.triangle] = 1;
  queue.push_back({first, second, start.third, start.triangle});
  for (size_t head = 0; head < queue.size(); ++head) {
    const QueuedTriangle t = queue[head];
    if (!done[t.n]) code(t.n, t.l, t.m);
    HalfEdges::Found next;
    // Right edge (l, n): the neighbour holds l → n.
    if (edges.find(t.l, t.n, next) && !labelled[next.triangle]) {
      labelled[next.triangle] = 1;
      queue.push_back({t.l, t.n, next.third, next.triangle});
    }
    // Left edge (m, n): the neighbour holds n → m.
    if (edges.find(t.n, t.m, next) && !labelled[next.triangle]) {
      labelled[next.triangle] = 1;
      queue.push_back({t.n, t.m, next.third, next.triangle});
    }
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

}  // namespace m4mesh
