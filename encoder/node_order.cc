// §10 node order for Delaunay I-planes.
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "encoder/mesh_object_encoder.h"

namespace m4mesh {

namespace {

// Remaining interior nodes bucketed on a grid over their bounding box, for
// nearest-L1 queries. Coordinates may be negative.
class NodeGrid {
 public:
  NodeGrid(std::span<const Point> nodes, std::span<const NodeIndex> members) : nodes_(nodes) {
    if (!members.empty()) {
      int64_t max_x = nodes[members[0]].x, max_y = nodes[members[0]].y;
      min_x_ = max_x;
      min_y_ = max_y;
      for (NodeIndex i : members) {
        min_x_ = std::min<int64_t>(min_x_, nodes[i].x);
        min_y_ = std::min<int64_t>(min_y_, nodes[i].y);
        max_x = std::max<int64_t>(max_x, nodes[i].x);
        max_y = std::max<int64_t>(max_y, nodes[i].y);
      }
      side_ = std::max<int32_t>(1, static_cast<int32_t>(std::sqrt(static_cast<double>(members.size()) / 2.0)));
      cell_ = std::max(max_x - min_x_, max_y - min_y_) / side_ + 1;
    }
    cells_.resize(static_cast<size_t>(side_) * side_);
    for (NodeIndex i : members) cells_[static_cast<size_t>(row(nodes[i])) * side_ + column(nodes[i])].push_back(i);
  }

  // Removes and returns the node nearest to `from` (L1, then smaller y, then smaller x).
  NodeIndex take_nearest(const Point& from) {
    const int32_t cx = column(from), cy = row(from);
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
  // The grid column and row of a point, clamped to the grid.
  int32_t column(const Point& p) const { return static_cast<int32_t>(std::clamp<int64_t>((p.x - min_x_) / cell_, 0, side_ - 1)); }
  int32_t row(const Point& p) const { return static_cast<int32_t>(std::clamp<int64_t>((p.y - min_y_) / cell_, 0, side_ - 1)); }

  std::span<const Point> nodes_;
  int64_t min_x_ = 0, min_y_ = 0;
  int32_t side_ = 1;
  int64_t cell_ = 1;
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
