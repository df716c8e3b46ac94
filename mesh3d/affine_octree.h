// The normative process of the Affine-Octree codec (codec_id 2,
// docs/codec_affine_octree.md), shared by its encoder and decoder: the root cube of the previous decoded
// frame, the octree cells its vertices fall into, and the integer affine
// reconstruction. Integers only, so every platform finds the same cells.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "syntax/mesh3d/affine_octree.h"

namespace m4mesh {

// The tight bounding cube of a frame in grid units: the per-axis minimum and
// the largest extent (at least 1) as the side.
struct RootCube {
  std::array<int64_t, 3> min{};
  int64_t side = 1;
};
RootCube root_cube(std::span<const IntPoint3> positions);

struct OctreeCell {
  int depth = 0;
  std::array<int64_t, 3> index{};   // the cell's coordinates among the 2^depth per axis
  std::array<int64_t, 3> corner{};  // its lower corner: min + floor(index · side / 2^depth)
  std::span<const uint32_t> vertices;  // increasing vertex order
};

// Walks the octree of a frame depth first: visit(cell) is called for every
// cell holding at least one vertex and returns whether the cell splits;
// children follow in the order x + 2y + 4z of their lower/upper halves.
// A vertex goes to the upper half of an axis when
// (p − min) · 2^(depth+1) ≥ (2 · index + 1) · side.
class OctreePartition {
 public:
  template <class Visit>
  void walk(std::span<const IntPoint3> positions, const RootCube& cube, Visit&& visit) {
    order_.resize(positions.size());
    for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
    sorted_.resize(order_.size());
    child_.resize(order_.size());
    OctreeCell root;
    root.corner = cube.min;
    visit_cell(positions, cube, root, 0, order_.size(), visit);
  }

 private:
  template <class Visit>
  void visit_cell(std::span<const IntPoint3> positions, const RootCube& cube, OctreeCell& cell, size_t begin, size_t end,
                  Visit& visit) {
    cell.vertices = std::span<const uint32_t>(order_).subspan(begin, end - begin);
    if (!visit(static_cast<const OctreeCell&>(cell))) return;
    std::array<size_t, 9> start{};
    split(positions, cube, cell, begin, end, start);
    for (int child = 0; child < 8; ++child) {
      if (start[child] == start[child + 1]) continue;
      OctreeCell c;
      c.depth = cell.depth + 1;
      for (int axis = 0; axis < 3; ++axis) {
        c.index[axis] = 2 * cell.index[axis] + ((child >> axis) & 1);
        c.corner[axis] = cube.min[axis] + ((c.index[axis] * cube.side) >> c.depth);
      }
      visit_cell(positions, cube, c, start[child], start[child + 1], visit);
    }
  }
  // A stable partition of order_[begin, end) by child; start[k] is where child k begins.
  void split(std::span<const IntPoint3> positions, const RootCube& cube, const OctreeCell& cell, size_t begin, size_t end,
             std::array<size_t, 9>& start);

  std::vector<uint32_t> order_, sorted_;
  std::vector<uint8_t> child_;
};

// Reconstruction by a decoded matrix Q with f fractional bits, per axis i:
// corner_i + ((Σ_j Q_ij (p_j − corner_j) + Q_i3 · side + 2^(f−1)) >> f),
// an arithmetic shift. |Q| < 2^23, |p|, |corner| ≤ 2^26 and side ≤ 2^27 keep
// every term within 64 bits.
inline std::array<int64_t, 3> apply_affine(const AffineMatrix& q, int fraction_bits, const std::array<int64_t, 3>& corner,
                                           int64_t side, const IntPoint3& p) {
  const int64_t d[3] = {p[0] - corner[0], p[1] - corner[1], p[2] - corner[2]};
  const int64_t half = int64_t{1} << fraction_bits >> 1;
  std::array<int64_t, 3> out;
  for (int i = 0; i < 3; ++i) {
    const int32_t* row = &q[static_cast<size_t>(4 * i)];
    out[i] = corner[i] + ((row[0] * d[0] + row[1] * d[1] + row[2] * d[2] + row[3] * side + half) >> fraction_bits);
  }
  return out;
}

}  // namespace m4mesh
