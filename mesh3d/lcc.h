// The normative process of the local-cylindrical-coordinate cloth codec
// (codec_id 3, ../shared/seeds/001: Chen et al.), shared by its encoder and
// decoder: the traversal of a spanning tree of the dual graph, the local
// cylindrical frame of a triangle, and the sines and cosines of the
// quantized angles. Decoding uses IEEE +, −, ×, / and sqrt in a fixed
// order only (no libm transcendental function, no FMA contraction), so it
// is bit-exact on every platform.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"
#include "mesh3d/sequence.h"
#include "syntax/mesh3d/lcc.h"

namespace m4mesh {

// Vertex d is coded in the cylinder of triangle (a, b, c) around its edge
// b → c (the edge it shares with the triangle that reaches d).
struct LccStep {
  NodeIndex d, a, b, c;
};

// The coding order, from the faces alone: per component (started at the
// first face, in list order, not yet reached), the root face's vertices not
// yet coded are coded directly; then a depth-first walk of the dual graph,
// whose neighbours are the triangles across each edge in the face's order
// v0 → v1, v1 → v2, v2 → v0 (the first triangle in list order holding the
// reverse edge), codes each reached triangle's third vertex, when not yet
// coded, in the cylinder of the triangle it is reached from. Vertices in
// no face are coded directly, in index order, at the end.
struct LccOrder {
  std::vector<NodeIndex> direct;
  std::vector<LccStep> steps;  // every step refers only to vertices coded before it
};
LccOrder lcc_order(std::span<const Triangle> faces, size_t vertex_count);

// The order of the frame units, generated one at a time. Without temporal
// prediction (gop 0) every frame is an anchor, in display order. With it,
// anchors every `gop` frames from the first coded frame, and the last
// frame; after each anchor, the frames between it and the anchor before,
// midpoint first: frame m = l + ⌊(r − l)/2⌋ is predicted from l and r,
// then (l, m) and (m, r) the same way (the hierarchy of the paper's [23]).
inline constexpr uint32_t kLccAnchor = 0xFFFFFFFF;
struct LccCodedFrame {
  uint32_t frame;
  uint32_t left = kLccAnchor, right = kLccAnchor;  // the frames it is predicted from
  bool anchor() const { return left == kLccAnchor; }
};
class LccFrameOrder {
 public:
  // frame_count 0: unknown, endless (gop 0 only).
  LccFrameOrder(uint32_t first, uint32_t frame_count, uint32_t gop) : frame_count_(frame_count), gop_(gop), anchor_(first) {}
  bool done() const { return pending_.empty() && frame_count_ != 0 && anchor_ >= frame_count_; }
  LccCodedFrame next();

 private:
  uint64_t frame_count_, gop_, anchor_;
  uint64_t previous_ = kLccAnchor;
  std::vector<std::pair<uint32_t, uint32_t>> pending_;  // intervals (l, r) still to fill, the next last
};

// The local cylindrical frame of triangle (a, b, c) around edge b → c:
// origin the edge's middle, axis z along b → c, polar axis x = z × n
// (n the triangle's unit normal: x points away from a, so a flat
// continuation has θ = 0) and y = n. A degenerate triangle borrows
// fixed axes (the .cc says which), the same on both sides.
struct LccFrame {
  Vec3 origin, x, y, z;
};
LccFrame lcc_frame(const Vec3& a, const Vec3& b, const Vec3& c);

// Cylindrical coordinates of p in a frame (the encoder's measurement: θ
// in [−π, π] within 10^−9, from an arc tangent decoding never needs).
struct Cylindrical {
  double theta = 0, radius = 0, height = 0;
};
Cylindrical to_cylindrical(const LccFrame& frame, const Vec3& p);
// The radius and height alone, without any transcendental function.
Cylindrical radius_and_height(const LccFrame& frame, const Vec3& p);
// origin + radius·(cos θ·x + sin θ·y) + height·z.
Vec3 from_cylindrical(const LccFrame& frame, double cos_theta, double sin_theta, double radius, double height);

// cos and sin of the 2^bits angles 2π·k / 2^bits, k = −2^(bits−1) …
// 2^(bits−1) − 1, computed by fixed polynomials; index k + 2^(bits−1);
// bits 3 … 24.
class AngleTable {
 public:
  explicit AngleTable(int bits);
  double cos(size_t index) const { return cos_[index]; }
  double sin(size_t index) const { return sin_[index]; }

 private:
  std::vector<double> cos_, sin_;
};

// Steps are placed a chunk at a time (the decoder's symbols arrive in chunks).
inline constexpr size_t kLccStepChunk = 1024;

// What decoding a frame needs, fixed for the stream after the reference
// mesh: the coding order, the reference's own radius and height at every
// step, the average edge length L of the reference, the angle table and
// the dequantization steps. θ has 2^(b_θ+1) values, index t in
// [−2^b_θ, 2^b_θ): θ = t·π / 2^b_θ; ρ and ζ have indices in
// [−2^b_rh, 2^b_rh], standing for index·σ / 2^b_rh.
class LccModel {
 public:
  LccModel(std::span<const Triangle> faces, std::span<const Vec3> reference, int theta_bits, int rh_bits, double rh_range);

  const LccOrder& order() const { return order_; }
  double edge_length() const { return edge_length_; }
  int32_t theta_limit() const { return theta_limit_; }
  int32_t rh_limit() const { return rh_limit_; }
  double rh_step() const { return rh_step_; }
  // The reference's radius and height at step k, divided by L.
  double reference_radius(size_t k) const { return reference_radius_[k]; }
  double reference_height(size_t k) const { return reference_height_[k]; }

  // Step k's vertex from the positions reconstructed so far and its
  // indices: in the frame of the reconstructed (a, b, c), radius
  // (ρ̂ + r*)·L and height (ζ̂ + z*)·L.
  Vec3 place(size_t k, std::span<const Vec3> positions, int32_t theta, int32_t rho, int32_t zeta) const {
    const LccStep& step = order_.steps[k];
    return place_in(lcc_frame(positions[step.a], positions[step.b], positions[step.c]), k, theta, rho, zeta);
  }
  // The same in step k's frame, already built.
  Vec3 place_in(const LccFrame& frame, size_t k, int32_t theta, int32_t rho, int32_t zeta) const;
  // place() for every step of chunk `chunk` (steps chunk · kLccStepChunk
  // onwards, its vertices' positions before it in `positions`), each from
  // its indices (t, i, j at 3k): the values of place() in coding order,
  // computed two steps at a time where neither waits for the other.
  void place_chunk(size_t chunk, std::span<const int32_t> indices, std::span<Vec3> positions) const;

 private:
  // Two steps of a chunk placed together; second is kAlone for a step placed by itself.
  struct StepPair {
    static constexpr uint32_t kAlone = UINT32_MAX;
    uint32_t first, second;
  };
  void pair_steps(size_t vertex_count);
  void place_pair(const StepPair& pair, std::span<const int32_t> indices, std::span<Vec3> positions) const;

  LccOrder order_;
  std::vector<StepPair> pairs_;      // chunk by chunk, by depth within the chunk
  std::vector<uint32_t> chunk_pairs_;  // the first pair of each chunk, and their end
  std::vector<double> reference_radius_, reference_height_;
  double edge_length_ = 1;
  int32_t theta_limit_, rh_limit_;
  double rh_step_;
  AngleTable angles_;
};

// A coded frame's quantized values: the directly coded vertices' grid
// indices (x, y, z each, in the order's direct order) and every step's
// angle, radius and height indices (t, i, j).
struct LccIndices {
  std::vector<int32_t> direct, steps;
};

// An angle index t wrapped into [−limit, limit) (θ into [−π, π)).
inline int32_t lcc_wrapped_angle(int64_t t, int32_t limit) {
  const int64_t n = 2 * int64_t{limit};
  return static_cast<int32_t>(((t + limit) % n + n) % n - limit);
}

// The prediction of each coded frame's indices, the same on both sides.
// Anchor: the grid indices of the reference (stream mode) or of the
// previous anchor (download mode; the reference before the first), and 0
// for t, i and j. A frame between anchors l and r: the means ⌊(l + r)/2⌋
// of their indices, and for t the midpoint along the shorter arc,
// l + ⌊wrap(r − l)/2⌋ wrapped.
class LccPredictor {
 public:
  LccPredictor(const LccHeader& header, const LccOrder& order, std::span<const IntPoint3> reference_grid);

  const LccIndices& predict(const LccCodedFrame& coded);
  // Keeps a coded frame's indices for the frames predicted from it; an
  // anchor drops every frame before the previous anchor.
  void keep(const LccCodedFrame& coded, LccIndices indices);

 private:
  bool download_;
  int32_t theta_limit_;
  LccIndices reference_, prediction_;
  const LccIndices& kept(uint32_t frame) const;

  // The frames from the previous anchor to the last one, by frame −
  // window_start_ (at most gop + 1).
  std::vector<LccIndices> window_;
  uint32_t window_start_ = 0, last_anchor_ = 0;
};

// A grid index's position in binary64: origin + q·step per axis (the
// directly coded vertices and the reference mesh).
Vec3 lcc_grid_position(const LccHeader& header, const IntPoint3& q);

// The average edge length of a mesh: every face's three edges (an inner
// edge so counts twice), summed in face order; 1 when that is not positive.
double average_edge_length(std::span<const Triangle> faces, std::span<const Vec3> positions);

}  // namespace m4mesh
