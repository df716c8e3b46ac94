// Node motion estimation for a 2D mesh object: where each node of a mesh
// laid on the first frame lies in every later frame. Hierarchical: on the
// coarsest level of an image pyramid each node's polygon (its triangles)
// is matched by translation (full search); on every level down to full
// size, nodes then move one by one to the neighbouring position that
// lowers the warp error of their polygon most (the hexagonal matching of
// Nakaya & Harashima), ending on the half-pixel grid the syntax carries.
// Every frame starts from the global motion (global_motion.h), so pans
// and zooms of tens of pixels are followed. A move that would fold a
// triangle over (orient ≤ 0) or change its area more than kMaxStretch
// times is never taken, so the topology of the first frame holds in every
// frame and no triangle is drawn across an object moving past.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"
#include "video/tracking/global_motion.h"
#include "video/tracking/luma.h"

namespace m4mesh {

// How a node may move when the border is held on the frame
// (TrackerOptions::border_on_frame): freely, not at all (a frame corner),
// or along the frame edge it lies on, inside the first frame's mesh
// rectangle. Otherwise every node moves with the content under it.
enum class NodeFreedom : uint8_t { kFree, kFixed, kAlongX, kAlongY };

struct TrackingMesh {
  std::vector<Point> nodes;          // half pixels, on the first frame
  std::vector<Triangle> triangles;   // clockwise (orient > 0)
  std::vector<NodeFreedom> freedom;  // per node
};

// What a frame is matched against: the first frame (the texture the
// decoder warps; no drift) or the previous frame.
enum class TrackingReference { kFirst, kPrevious };

struct TrackerOptions {
  uint32_t search = 16;  // pixels a polygon's translation is searched, each way
  int levels = -1;       // pyramid levels above full size (0 … 4); −1 chooses
  TrackingReference reference = TrackingReference::kFirst;
  int sweeps = 4;  // most descent sweeps per level and step
  // Border nodes held on the frame's edges (the mesh always covers the
  // frame: motion compensation), instead of following the content.
  bool border_on_frame = false;
};

// The most a node moves between frames, in half pixels: a P-plane's vectors
// fit motion_range_code 3 ([−128, 127]).
inline constexpr int32_t kMaxNodeMotion = 127;

// The most a triangle's area grows or shrinks from the first frame: a
// node dragged further by an object moving past its neighbours stops.
inline constexpr double kMaxStretch = 4;

class NodeTracker {
 public:
  NodeTracker(TrackingMesh mesh, const Luma& first, const TrackerOptions& options);

  // The node positions in the next frame (half pixels, the first frame's
  // node indices): no triangle folded, each node within kMaxNodeMotion of
  // its previous position.
  const std::vector<Point>& track(const Luma& frame);
  const std::vector<Point>& positions() const { return positions_; }
  int levels() const { return levels_; }
  // The last frame's global motion: from the first frame (or, matching
  // against the previous frame, from that one).
  const Affine& global() const { return global_; }

 private:
  struct Sample {
    float b1, b2;  // barycentric weights of corners 1 and 2 in the reference triangle
    float value;   // the reference picture at that pixel centre
  };
  using Position = std::array<double, 2>;  // pixels of a pyramid level

  NodeFreedom freedom(uint32_t node) const { return options_.border_on_frame ? mesh_.freedom[node] : NodeFreedom::kFree; }
  void build_samples(const std::vector<Luma>& reference, const std::vector<Point>& at);
  std::vector<Position> start(const Affine& global) const;
  void place_on_content(std::vector<Position>& p, const std::vector<Position>& started, const Affine& global) const;
  using Linear = std::array<double, 4>;  // a 2×2 matrix, row by row
  std::optional<Linear> ring_shape(uint32_t node, const std::vector<Position>& p, const std::vector<Point>& origin, const Affine& global) const;
  double triangle_cost(int level, uint32_t t, const std::vector<Position>& p, NodeIndex moved, const Position& to) const;
  // Whether every triangle around `node` at `to` (positions of a level of `scale`) keeps clockwise, within kMaxStretch of its first area.
  bool keeps_shape(uint32_t node, const Position& to, const std::vector<Position>& p, double scale) const;
  bool allowed(uint32_t node, const Position& to, double scale) const;
  void translate_polygons(int level, std::vector<Position>& p, double scale);
  void descend(int level, std::vector<Position>& p, double scale, double step);

  TrackingMesh mesh_;
  TrackerOptions options_;
  int levels_ = 0;
  std::vector<std::vector<uint32_t>> node_triangles_;
  std::vector<double> design_area_;  // per triangle, on the first frame, pixels²
  double x_lo_ = 0, x_hi_ = 0, y_lo_ = 0, y_hi_ = 0;  // the first frame's mesh rectangle, pixels
  std::vector<std::vector<std::vector<Sample>>> samples_;  // [level][triangle]
  std::vector<Luma> frame_pyramid_, previous_pyramid_;
  std::vector<Point> positions_;
  std::vector<double> costs_;  // per triangle, at the current level and positions
  std::vector<bool> outside_;  // per node: its start lies out of the frame
  bool has_velocity_ = false;
  Affine global_, global_before_;
};

}  // namespace m4mesh
