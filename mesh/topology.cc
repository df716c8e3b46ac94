#include "mesh/topology.h"

#include <algorithm>

namespace m4mesh {

std::vector<Triangle> canonical_triangles(std::span<const Triangle> triangles, std::span<const Point> nodes) {
  // Bucket by the smallest index (a counting sort), then order each small bucket.
  std::vector<Triangle> rotated(triangles.begin(), triangles.end());
  std::vector<uint32_t> start(nodes.size() + 1, 0);
  for (Triangle& t : rotated) {
    if (orient(nodes[t.v[0]], nodes[t.v[1]], nodes[t.v[2]]) < 0) std::swap(t.v[1], t.v[2]);
    std::rotate(t.v.begin(), std::min_element(t.v.begin(), t.v.end()), t.v.end());
    ++start[t.v[0] + 1];
  }
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<Triangle> out(rotated.size());
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (const Triangle& t : rotated) out[fill[t.v[0]]++] = t;
  for (size_t i = 0; i + 1 < start.size(); ++i)
    std::sort(out.begin() + start[i], out.begin() + start[i + 1]);
  return out;
}

bool same_faces(std::span<const Triangle> a, std::span<const Triangle> b) {
  if (a.size() != b.size()) return false;
  const auto sorted = [](std::span<const Triangle> faces) {
    std::vector<Triangle> out(faces.begin(), faces.end());
    for (Triangle& t : out) std::rotate(t.v.begin(), std::min_element(t.v.begin(), t.v.end()), t.v.end());
    std::sort(out.begin(), out.end());
    return out;
  };
  return sorted(a) == sorted(b);
}

TriangleNeighbours triangle_neighbours(std::span<const Triangle> triangles, size_t node_count) {
  // Directed edges grouped by their first node.
  std::vector<uint32_t> first(node_count + 1, 0);
  for (const Triangle& t : triangles)
    for (NodeIndex from : t.v) ++first[from + 1];
  for (size_t i = 1; i <= node_count; ++i) first[i] += first[i - 1];
  struct Edge {
    NodeIndex to;
    uint32_t triangle;
  };
  std::vector<Edge> edges(triangles.size() * 3);
  std::vector<uint32_t> fill(first.begin(), first.end() - 1);
  for (uint32_t k = 0; k < triangles.size(); ++k)
    for (int j = 0; j < 3; ++j) edges[fill[triangles[k].v[j]]++] = Edge{triangles[k].v[(j + 1) % 3], k};

  // Each node's edges by their end, then by triangle: the first edge a → b
  // found is that of the lowest triangle, and a node of any degree is
  // searched in logarithmic time.
  for (size_t n = 0; n < node_count; ++n)
    std::sort(edges.begin() + first[n], edges.begin() + first[n + 1],
              [](const Edge& x, const Edge& y) { return x.to != y.to ? x.to < y.to : x.triangle < y.triangle; });

  TriangleNeighbours neighbours(triangles.size(), {kNoTriangle, kNoTriangle, kNoTriangle});
  for (uint32_t k = 0; k < triangles.size(); ++k) {
    for (int j = 0; j < 3; ++j) {
      // The edge opposite v[j] runs v[j+1] → v[j+2]; its neighbour holds v[j+2] → v[j+1].
      const NodeIndex a = triangles[k].v[(j + 2) % 3], b = triangles[k].v[(j + 1) % 3];
      const auto begin = edges.begin() + first[a], end = edges.begin() + first[a + 1];
      const auto e = std::lower_bound(begin, end, b, [](const Edge& x, NodeIndex to) { return x.to < to; });
      if (e != end && e->to == b) neighbours[k][j] = e->triangle;
    }
  }
  return neighbours;
}

}  // namespace m4mesh
