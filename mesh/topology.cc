#include "mesh/topology.h"

#include <algorithm>
#include <span>

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
  // Directed edges grouped by their first node, each group in triangle order; an edge leaves v[corner].
  std::vector<uint32_t> first(node_count + 1, 0);
  for (const Triangle& t : triangles)
    for (NodeIndex from : t.v) ++first[from + 1];
  for (size_t i = 1; i <= node_count; ++i) first[i] += first[i - 1];
  struct Edge {
    NodeIndex to;
    uint32_t triangle, corner;
  };
  std::vector<Edge> edges(triangles.size() * 3);
  std::vector<uint32_t> fill(first.begin(), first.end() - 1);
  for (uint32_t k = 0; k < triangles.size(); ++k)
    for (uint32_t j = 0; j < 3; ++j) edges[fill[triangles[k].v[j]]++] = Edge{triangles[k].v[(j + 1) % 3], k, j};

  // Node by node: the first (lowest) triangle of each edge a → b, then the
  // neighbour of every triangle across its edge b → a, which lies opposite
  // the corner after a's. Linear whatever the degrees.
  TriangleNeighbours neighbours(triangles.size(), {kNoTriangle, kNoTriangle, kNoTriangle});
  std::vector<uint32_t> seen_from(node_count, kNoNode), first_triangle(node_count);
  for (uint32_t a = 0; a < node_count; ++a) {
    const std::span<const Edge> from_a(edges.data() + first[a], edges.data() + first[a + 1]);
    for (const Edge& e : from_a)
      if (seen_from[e.to] != a) seen_from[e.to] = a, first_triangle[e.to] = e.triangle;
    for (const Edge& e : from_a) {
      const NodeIndex b = triangles[e.triangle].v[(e.corner + 2) % 3];
      if (seen_from[b] == a) neighbours[e.triangle][(e.corner + 1) % 3] = first_triangle[b];
    }
  }
  return neighbours;
}

}  // namespace m4mesh
