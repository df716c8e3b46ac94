// Affine-Octree (codec_id 2) syntax (docs/codec_affine_octree.md): the codec
// header, a frame unit's data (fixed fields, a bin section and a raw bit
// section) and the syntax of one octree cell, each described once for
// reading, writing, counting and tracing.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "common/bit_cast.h"
#include "syntax/io.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

inline constexpr int kAffineElements = 12;  // a 3 × 4 matrix, row-major; column 3 is the translation
using AffineMatrix = std::array<int32_t, kAffineElements>;

struct AffineOctreeHeader {
  uint32_t bits = 12;                // quantization bits of the grid over the first frame's box
  std::array<uint32_t, 3> origin{};  // binary32 bit patterns
  uint32_t step = 0;                 // binary32: one step for every axis
  uint32_t matrix_bits = 16;         // k: bits per matrix element
  uint32_t matrix_range_log2 = 2;    // elements lie in [−2^(r−1), 2^(r−1))
  uint32_t max_depth = 16;

  float origin_value(int axis) const { return bit_cast<float>(origin[axis]); }
  float step_value() const { return bit_cast<float>(step); }
  // A matrix element q stands for q / 2^fraction_bits.
  int fraction_bits() const { return static_cast<int>(matrix_bits - matrix_range_log2); }
  int32_t matrix_min() const { return -(int32_t{1} << (matrix_bits - 1)); }
  int32_t matrix_max() const { return (int32_t{1} << (matrix_bits - 1)) - 1; }
};

inline constexpr uint32_t kMaxOctreeDepth = 20;
inline constexpr uint32_t kMaxDirectShift = 26;
inline constexpr int kDepthContexts = 16;
// Residual channels: the 12 matrix elements, then the 3 axes of direct motion.
inline constexpr int kDirectChannel = kAffineElements;
inline constexpr int kAffineChannels = kAffineElements + 3;
// A cell with at most this many vertices codes their motion directly.
inline constexpr size_t kMaxDirectCellVertices = 4;

// A frame unit's data: two fields, the bins, the raw bits to the end.
struct AffineFrame {
  uint32_t direct_shift = 0;
  uint32_t arithmetic_bytes = 0;
  std::span<const uint8_t> bins;
  std::span<const uint8_t> raw;
};

namespace syntax {

inline constexpr ResidualNames kMatrixResidual = M4MESH_RESIDUAL_NAMES("matrix", "matrix_residual");
inline constexpr ResidualNames kDirectMotion = M4MESH_RESIDUAL_NAMES("direct", "direct_motion");

template <class IO>
void describe(IO& io, AffineFrame& f) {
  io.field_in("direct_shift", 8, f.direct_shift, 0, kMaxDirectShift);
  io.field("arithmetic_bytes", 32, f.arithmetic_bytes);
  io.require_length("arithmetic_bytes", f.arithmetic_bytes);
  io.section("bins", f.arithmetic_bytes, f.bins);
  io.tail_section("raw", f.raw);
}

template <class IO>
void describe(IO& io, AffineOctreeHeader& h) {
  io.field_in("quantization_bits", 8, h.bits, 4, 24);
  static const char* const kOrigin[3] = {"origin_x", "origin_y", "origin_z"};
  for (int axis = 0; axis < 3; ++axis) {
    binary32(io, kOrigin[axis], h.origin[axis]);
    io.require(std::isfinite(h.origin_value(axis)), ErrorKind::kOutOfRange, kOrigin[axis], "not a finite binary32");
  }
  binary32(io, "step", h.step);
  io.require(std::isfinite(h.step_value()) && h.step_value() > 0, ErrorKind::kOutOfRange, "step", "not a positive finite binary32");
  io.field_in("matrix_bits", 8, h.matrix_bits, 4, 24);
  io.field_in("matrix_range_log2", 8, h.matrix_range_log2, 1, 8);
  io.require(h.matrix_range_log2 < h.matrix_bits, ErrorKind::kOutOfRange, "matrix_range_log2",
             "leaves no fraction bits below matrix_bits");
  io.field_in("max_depth", 8, h.max_depth, 1, kMaxOctreeDepth);
}

}  // namespace syntax

// What one cell codes: a split, or a leaf with a matrix or with the direct
// motion of each of its vertices (in units of 2^direct_shift grid steps).
struct AffineCell {
  bool split = false;
  bool direct = false;
  AffineMatrix matrix{};
  std::vector<std::array<int32_t, 3>> motion;
};

// The adaptive state of one frame's cells. Matrix elements are coded as
// differences from the identity.
class AffineCellCoder {
 public:
  explicit AffineCellCoder(const AffineOctreeHeader& header) : header_(header) {
    identity_.fill(0);
    for (int i = 0; i < 3; ++i) identity_[static_cast<size_t>(5 * i)] = int32_t{1} << header.fraction_bits();
  }

  // The syntax of a cell with `count` ≥ 1 vertices at `depth`, through an
  // IO of syntax/mesh3d/entropy_io.h.
  template <class IO>
  void describe(IO& io, int depth, size_t count, AffineCell& cell) {
    const int context = std::min(depth, kDepthContexts - 1);
    if (count > kMaxDirectCellVertices) {
      if (depth < static_cast<int>(header_.max_depth))
        io.bin("split_flag", split_[context], context, cell.split);
      else
        cell.split = false;
      if (cell.split) return;
      io.bin("direct_flag", leaf_[context], context, cell.direct);
    } else {
      cell.split = false;
      cell.direct = true;
    }
    if (!cell.direct) {
      for (int e = 0; e < kAffineElements; ++e) {
        const size_t element = static_cast<size_t>(e);
        int32_t residual = cell.matrix[element] - identity_[element];
        residuals_.describe(io, e, residual, syntax::kMatrixResidual);
        const int64_t value = int64_t{identity_[element]} + residual;
        if (value < header_.matrix_min() || value > header_.matrix_max())
          io.fail(ErrorKind::kOutOfRange, "matrix_residual", "a matrix element outside matrix_bits");
        cell.matrix[element] = static_cast<int32_t>(value);
      }
      return;
    }
    cell.motion.resize(count);
    for (std::array<int32_t, 3>& motion : cell.motion)
      for (int axis = 0; axis < 3; ++axis) residuals_.describe(io, kDirectChannel + axis, motion[static_cast<size_t>(axis)], syntax::kDirectMotion);
  }

 private:
  const AffineOctreeHeader& header_;
  BinContext split_[kDepthContexts];
  BinContext leaf_[kDepthContexts];
  syntax::ResidualCoder<kAffineChannels> residuals_;
  AffineMatrix identity_;
};

}  // namespace m4mesh
