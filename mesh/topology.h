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

  // The corner that holds node n (the last corner when none does).
  int corner_of(NodeIndex n) const { return v[0] == n ? 0 : v[1] == n ? 1 : 2; }
  // The node that is neither a nor b.
  NodeIndex third(NodeIndex a, NodeIndex b) const {
    return v[0] != a && v[0] != b ? v[0] : v[1] != a && v[1] != b ? v[1] : v[2];
  }

  friend bool operator==(const Triangle&, const Triangle&) = default;
  // Lexicographic, for sorting (the web build's libc++ has no <=> on std::array).
  friend bool operator<(const Triangle& a, const Triangle& b) { return a.v < b.v; }
};

// §9 canonical form: each triangle clockwise (orient > 0) and rotated to
// start at its smallest index; the list sorted.
std::vector<Triangle> canonical_triangles(std::span<const Triangle> triangles, std::span<const Point> nodes);

// Whether two lists hold the same triangles, each with its orientation, in
// any order and any rotation (a 3D base mesh reorders and rotates faces).
bool same_faces(std::span<const Triangle> a, std::span<const Triangle> b);

inline constexpr uint32_t kNoTriangle = 0xFFFFFFFF;

// neighbours[t][i]: the triangle across the edge of t opposite t.v[i], or
// kNoTriangle on the border. Triangles must be consistently oriented.
using TriangleNeighbours = std::vector<std::array<uint32_t, 3>>;
TriangleNeighbours triangle_neighbours(std::span<const Triangle> triangles, size_t node_count);

// A triangle mesh over node indices with its adjacency.
struct MeshTopology {
  std::vector<Triangle> triangles;
  TriangleNeighbours neighbours;
};

}  // namespace m4mesh
