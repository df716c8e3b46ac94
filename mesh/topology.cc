#include "mesh/topology.h"

#include <algorithm>

namespace m4mesh {

std::vector<Triangle> canonical_triangles(std::span<const Triangle> triangles, std::span<const Point> nodes) {
  std::vector<Triangle> out(triangles.begin(), triangles.end());
  for (Triangle& t : out) {
    if (orient(nodes[t.v[0]], nodes[t.v[1]], nodes[t.v[2]]) < 0) std::swap(t.v[1], t.v[2]);
    std::rotate(t.v.begin(), std::min_element(t.v.begin(), t.v.end()), t.v.end());
  }
  std::sort(out.begin(), out.end());
  return out;
}

HalfEdges::HalfEdges(std::span<const Triangle> triangles, size_t node_count) : first_(node_count + 1, 0) {
  for (const Triangle& t : triangles)
    for (NodeIndex from : t.v) ++first_[from + 1];
  for (size_t i = 1; i <= node_count; ++i) first_[i] += first_[i - 1];
  edges_.resize(triangles.size() * 3);
  std::vector<uint32_t> fill(first_.begin(), first_.end() - 1);
  for (uint32_t k = 0; k < triangles.size(); ++k) {
    const Triangle& t = triangles[k];
    for (int j = 0; j < 3; ++j) edges_[fill[t.v[j]]++] = Edge{t.v[(j + 1) % 3], t.v[(j + 2) % 3], k};
  }
}

bool HalfEdges::find(NodeIndex a, NodeIndex b, Found& found) const {
  for (uint32_t i = first_[a]; i < first_[a + 1]; ++i) {
    if (edges_[i].to == b) {
      found = Found{edges_[i].triangle, edges_[i].third};
      return true;
    }
  }
  return false;
}

}  // namespace m4mesh
