// §10 node order for Delaunay I-planes.
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "encoder/encoder.h"

namespace m4mesh {

namespace {

// Remaining interior nodes bucketed on a grid, for nearest-L1 queries.
class NodeGrid {
 public:
  NodeGrid(std::span<const Point> nodes, std::span<const NodeIndex> members) : nodes_(nodes) {
    int32_t max_coordinate = 1;
    for (NodeIndex i : members) max_coordinate = std::max({max_coordinate, nodes[i].x, nodes[i].y});
    side_ = std::max<int32_t>(1, static_cast<int32_t>(std::sqrt(static_cast<double>(members.size()) / 2.0)));
    cell_ = max_coordinate / side_ + 1;
    cells_.resize(static_cast<size_t>(side_) * side_);
    for (NodeIndex i : members) cells_[cell_of(nodes[i])].push_back(i);
  }

  // Removes and returns the node nearest to `from` (L1, then smaller y, then smaller x).
  NodeIndex take_nearest(const Point& from) {
    const int32_t cx = std::clamp(from.x / cell_, 0, side_ - 1), cy = std::clamp(from.y / cell_, 0, side_ - 1);
    NodeIndex best = kNoNode;
    int64_t best_distance = 0;
    size_t best_cell = 0, best_slot = 0;
    for (int32_t ring = 0; ring < side_ * 2; ++ring) {
      if (best != kNoNode && int64_t{ring - 1} * cell_ + 1 > best_distance) break;
      for (int32_t y = cy - ring; y <= cy + ring; ++y) {
        if (y < 0 || y >= side_) continue;
        const bool edge_row = y == cy - ring || y == cy + ring;
        for (int32_t x = cx - ring; x <= cx + ring; x += edge_row ? 1 : 2 * ring) {
          if (x >= 0 && x < side_) {
            const size_t c = static_cast<size_t>(y) * side_ + x;
            for (size_t s = 0; s < cells_[c].size(); ++s) {
              const Point& p = nodes_[cells_[c][s]];
              const int64_t d = std::abs(int64_t{p.x} - from.x) + std::abs(int64_t{p.y} - from.y);
              if (best == kNoNode || d < best_distance ||
                  (d == best_distance && (p.y < nodes_[best].y || (p.y == nodes_[best].y && p.x < nodes_[best].x)))) {
                best = cells_[c][s];
                best_distance = d;
                best_cell = c;
                best_slot = s;
              }
            }
          }
          if (ring == 0) break;
        }
      }
    }
    cells_[best_cell][best_slot] = cells_[best_cell].back();
    cells_[best_cell].pop_back();
    return best;
  }

 private:
  size_t cell_of(const Point& p) const {
    return static_cast<size_t>(std::min(p.y / cell_, side_ - 1)) * side_ + std::min(p.x / cell_, side_ - 1);
  }

  std::span<const Point> nodes_;
  int32_t side_ = 1;
  int32_t cell_ = 1;
  std::vector<std::vector<NodeIndex>> cells_;
};

}  // namespace

std::vector<NodeIndex> delaunay_node_order(std::span<const Point> nodes, uint32_t boundary) {
  const uint32_t n = static_cast<uint32_t>(nodes.size());
  if (boundary < 3 || boundary > n)
    throw Error(ErrorKind::kGeometry, "", kNoPlane, kNoOffset,
                std::to_string(boundary) + " boundary nodes of " + std::to_string(n) + " nodes (3 … " + std::to_string(n) + " allowed)");
  NodeIndex top_left = 0;
  for (NodeIndex i = 1; i < n; ++i)
    if (more_top_left(nodes[i], nodes[top_left])) top_left = i;
  if (top_left >= boundary)
    throw Error(ErrorKind::kGeometry, "", kNoPlane, kNoOffset,
                "the top-left node " + std::to_string(top_left) + " is not a boundary node");
  int64_t area = 0;
  for (uint32_t i = 0; i < boundary; ++i) {
    const Point &p = nodes[i], &q = nodes[(i + 1) % boundary];
    area += int64_t{p.x} * q.y - int64_t{q.x} * p.y;
  }
  std::vector<NodeIndex> order;
  order.reserve(n);
  for (uint32_t k = 0; k < boundary; ++k) {
    const uint32_t step = area < 0 ? k : boundary - k;  // walk counterclockwise
    order.push_back((top_left + step) % boundary);
  }
  std::vector<NodeIndex> interior;
  for (NodeIndex i = boundary; i < n; ++i) interior.push_back(i);
  NodeGrid grid(nodes, interior);
  for (size_t k = 0; k < interior.size(); ++k) order.push_back(grid.take_nearest(nodes[order.back()]));
  return order;
}

}  // namespace m4mesh
