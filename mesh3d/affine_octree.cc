#include "mesh3d/affine_octree.h"

#include <algorithm>

namespace m4mesh {

RootCube root_cube(std::span<const IntPoint3> positions) {
  RootCube cube;
  if (positions.empty()) return cube;
  std::array<int64_t, 3> high{};
  for (int axis = 0; axis < 3; ++axis) cube.min[axis] = high[axis] = positions[0][axis];
  for (const IntPoint3& p : positions)
    for (int axis = 0; axis < 3; ++axis) {
      cube.min[axis] = std::min<int64_t>(cube.min[axis], p[axis]);
      high[axis] = std::max<int64_t>(high[axis], p[axis]);
    }
  for (int axis = 0; axis < 3; ++axis) cube.side = std::max(cube.side, high[axis] - cube.min[axis]);
  return cube;
}

void OctreePartition::split(std::span<const IntPoint3> positions, const RootCube& cube, const OctreeCell& cell, size_t begin,
                            size_t end, std::array<size_t, 9>& start) {
  std::array<int64_t, 3> threshold;
  for (int axis = 0; axis < 3; ++axis) threshold[axis] = (2 * cell.index[axis] + 1) * cube.side;
  const int shift = cell.depth + 1;
  std::array<size_t, 8> count{};
  for (size_t k = begin; k < end; ++k) {
    const IntPoint3& p = positions[order_[k]];
    int child = 0;
    for (int axis = 0; axis < 3; ++axis) child |= static_cast<int>(((p[axis] - cube.min[axis]) << shift) >= threshold[axis]) << axis;
    child_[k] = static_cast<uint8_t>(child);
    ++count[static_cast<size_t>(child)];
  }
  start[0] = begin;
  for (int child = 0; child < 8; ++child) start[child + 1] = start[child] + count[child];
  std::array<size_t, 8> next;
  std::copy(start.begin(), start.begin() + 8, next.begin());
  for (size_t k = begin; k < end; ++k) sorted_[next[child_[k]]++] = order_[k];
  std::copy(sorted_.begin() + static_cast<std::ptrdiff_t>(begin), sorted_.begin() + static_cast<std::ptrdiff_t>(end),
            order_.begin() + static_cast<std::ptrdiff_t>(begin));
}

}  // namespace m4mesh
