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
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/sequence.h"

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
// uses atan2, which decoding never needs).
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
  int bits() const { return bits_; }
  double cos(size_t index) const { return cos_[index]; }
  double sin(size_t index) const { return sin_[index]; }

 private:
  int bits_;
  std::vector<double> cos_, sin_;
};

}  // namespace m4mesh
