// Triangle lists and their adjacency.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/geometry.h"

namespace m4mesh {

using NodeIndex = uint32_t;
inline constexpr NodeIndex kNoNode = 0xFFFFFFFF;

struct Triangle {
  std::array<NodeIndex, 3> v;
  friend bool operator==(const Triangle&, const Triangle&) = default;
  friend auto operator<=>(const Triangle&, const Triangle&) = default;
};

// §9 canonical form: each triangle clockwise (orient > 0) and rotated to
// start at its smallest index; the list sorted.
std::vector<Triangle> canonical_triangles(std::span<const Triangle> triangles, std::span<const Point> nodes);

// Directed half-edges grouped by their first node, for finding the
// triangle on the other side of an edge in O(degree).
class HalfEdges {
 public:
  HalfEdges(std::span<const Triangle> triangles, size_t node_count);

  struct Found {
    uint32_t triangle;
    NodeIndex third;  // the triangle's node opposite the edge
  };
  // The triangle holding the directed edge a → b, if any.
  bool find(NodeIndex a, NodeIndex b, Found& found) const;

 private:
  std::vector<uint32_t> first_;  // per node, start in edges_
  struct Edge {
    NodeIndex to;
    NodeIndex third;
    uint32_t triangle;
  };
  std::vector<Edge> edges_;
};

}  // namespace m4mesh
