#include "mesh3d/bfs3d.h"

namespace m4mesh {

namespace {

struct Queued {
  NodeIndex l, m, n, c;  // ⟨l, m, n⟩ with base edge (l, m); c: the node across it (or zero)
  uint32_t face;
};

}  // namespace

MotionOrder3d bfs3d_order(std::span<const Triangle> faces, size_t vertex_count) {
  MotionOrder3d order;
  const NodeIndex zero = static_cast<NodeIndex>(vertex_count);
  order.zero_slot = zero;
  std::vector<uint8_t> done(vertex_count, 0);
  auto code = [&](NodeIndex node, NodeIndex a, NodeIndex b, NodeIndex c) {
    if (done[node]) return;
    done[node] = 1;
    order.node.push_back(node);
    order.pred_a.push_back(a);
    order.pred_b.push_back(b);
    order.pred_c.push_back(c);
  };
  const TriangleNeighbours neighbours = triangle_neighbours(faces, vertex_count);
  std::vector<uint8_t> labelled(faces.size(), 0);
  std::vector<Queued> queue;
  queue.reserve(faces.size());
  auto enqueue = [&](uint32_t f, NodeIndex across, NodeIndex base0, NodeIndex base1) {
    const uint32_t next = neighbours[f][faces[f].corner_of(across)];
    if (next == kNoTriangle || labelled[next]) return;
    labelled[next] = 1;
    queue.push_back({base0, base1, faces[next].third(base0, base1), across, next});
  };
  for (uint32_t start = 0; start < faces.size(); ++start) {
    if (labelled[start]) continue;
    const Triangle& t = faces[start];
    code(t.v[0], zero, zero, zero);
    code(t.v[1], t.v[0], t.v[0], zero);
    labelled[start] = 1;
    queue.clear();
    queue.push_back({t.v[0], t.v[1], t.v[2], zero, start});
    for (size_t head = 0; head < queue.size(); ++head) {
      const Queued q = queue[head];
      code(q.n, q.l, q.m, q.c);
      enqueue(q.face, q.m, q.l, q.n);  // right edge (l, n): ⟨l, n, ·⟩, across it from m
      enqueue(q.face, q.l, q.n, q.m);  // left edge (m, n): ⟨n, m, ·⟩, across it from l
    }
  }
  for (NodeIndex v = 0; v < vertex_count; ++v) code(v, zero, zero, zero);
  return order;
}

}  // namespace m4mesh
