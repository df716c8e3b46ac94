// bfs3d (codec_id 1) syntax: the codec header that follows the object
// header (docs/container3d.md); residuals use syntax/residual_coder.h.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

#include "mesh3d/traversal3d.h"
#include "syntax/io.h"

namespace m4mesh {

// The lengths that open a frame unit's data. Each axis has its own
// arithmetic-coded bin stream and its own raw bit stream (MSB first,
// zero-padded to a byte), which follow the lengths in the order
// bins x, raw x, bins y, raw y, bins z, raw z; a decoder can decode each
// axis on its own.
struct Bfs3dFrameLengths {
  std::array<uint32_t, 3> arithmetic_bytes{};
  std::array<uint32_t, 3> raw_bytes{};

  uint64_t streams_bytes() const {
    uint64_t total = 0;
    for (int axis = 0; axis < 3; ++axis) total += uint64_t{arithmetic_bytes[axis]} + raw_bytes[axis];
    return total;
  }
};
inline constexpr size_t kBfs3dLengthsBytes = 24;

inline constexpr uint32_t kPredictAverage = 0;
inline constexpr uint32_t kPredictParallelogram = 1;

// The predicted motion of the k-th coded vertex from the motion of the
// vertices coded before it: the average of its base edge's ends (a, b), or
// with `parallelogram` and a vertex c across that edge, a + b − c.
inline std::array<int64_t, 3> predict_motion(const MotionOrder3d& order, size_t k, std::span<const std::array<int32_t, 3>> motion,
                                             bool parallelogram) {
  const auto &a = motion[order.pred_a[k]], &b = motion[order.pred_b[k]], &c = motion[order.pred_c[k]];
  const bool use_parallelogram = parallelogram && order.pred_c[k] != order.zero_slot;
  std::array<int64_t, 3> w;
  for (int axis = 0; axis < 3; ++axis)
    w[axis] = use_parallelogram ? int64_t{a[axis]} + b[axis] - c[axis] : (int64_t{a[axis]} + b[axis] + 1) >> 1;
  return w;
}

struct Bfs3dHeader {
  uint32_t bits = 12;  // quantization bits per coordinate over the first frame's box
  uint32_t prediction = kPredictAverage;
  std::array<uint32_t, 3> origin{};  // binary32 bit patterns
  std::array<uint32_t, 3> step{};

  float origin_value(int axis) const { return std::bit_cast<float>(origin[axis]); }
  float step_value(int axis) const { return std::bit_cast<float>(step[axis]); }
};

namespace syntax {

template <class IO>
void describe(IO& io, Bfs3dHeader& h) {
  io.field_in("quantization_bits", 8, h.bits, 4, 24);
  io.field_in("prediction_mode", 8, h.prediction, kPredictAverage, kPredictParallelogram);
  static const char* const kOrigin[3] = {"origin_x", "origin_y", "origin_z"};
  static const char* const kStep[3] = {"step_x", "step_y", "step_z"};
  for (int axis = 0; axis < 3; ++axis) {
    io.field(kOrigin[axis], 32, h.origin[axis]);
    io.require(std::isfinite(h.origin_value(axis)), ErrorKind::kOutOfRange, kOrigin[axis], "not a finite binary32");
    io.field(kStep[axis], 32, h.step[axis]);
    io.require(std::isfinite(h.step_value(axis)) && h.step_value(axis) > 0, ErrorKind::kOutOfRange, kStep[axis],
               "not a positive finite binary32");
  }
}

template <class IO>
void describe(IO& io, Bfs3dFrameLengths& l) {
  static const char* const kArithmetic[3] = {"arithmetic_bytes_x", "arithmetic_bytes_y", "arithmetic_bytes_z"};
  static const char* const kRaw[3] = {"raw_bytes_x", "raw_bytes_y", "raw_bytes_z"};
  for (int axis = 0; axis < 3; ++axis) {
    io.field(kArithmetic[axis], 32, l.arithmetic_bytes[axis]);
    io.field(kRaw[axis], 32, l.raw_bytes[axis]);
  }
}

}  // namespace syntax

}  // namespace m4mesh
