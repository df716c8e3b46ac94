// bfs3d (codec_id 1) syntax: the codec header that follows the object
// header, and the binarization of motion residuals (docs/codec_bfs3d.md).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "bitstream/arithmetic.h"
#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"
#include "syntax/io.h"

namespace m4mesh {

// A frame unit's data: three arithmetic_bytes u(32), one per coordinate
// axis, the three arithmetic-coded bin streams in that order (independent
// engines, so a decoder can overlap them), then the raw bits (MSB first,
// zero-padded to a byte).
inline constexpr size_t kArithmeticLengthBytes = 4;

inline constexpr uint32_t kPredictAverage = 0;
inline constexpr uint32_t kPredictParallelogram = 1;

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

}  // namespace syntax

// The residual binarization: a zero flag per coordinate and class of the
// previous residual of that coordinate, then |r| − 1 in exp-Golomb of
// order k, where k follows a running mean of the coordinate's magnitudes.
// The zero flag and the prefix bins are arithmetic-coded with adaptive
// contexts; the sign and the e + k suffix bits, equiprobable, are raw bits
// in the frame's raw section.
class ResidualModel {
 public:
  static constexpr int kClasses = 3;
  static constexpr int kPrefixContexts = 12;
  static constexpr int kMaxPrefix = 30;  // |r| < 2^31

  void encode(ArithmeticEncoder& coder, BitWriter& raw, int axis, int32_t r) {
    const int cls = previous_[axis];
    coder.encode(nonzero_[axis][cls], r != 0);
    if (r == 0) {
      update(axis, 0);
      return;
    }
    raw.write_bit(r < 0);
    const uint32_t magnitude = static_cast<uint32_t>(r < 0 ? -static_cast<int64_t>(r) : r);
    const int k = order(axis);
    const uint32_t m = magnitude - 1;
    const uint32_t high = (m >> k) + 1;  // ≥ 1
    const int e = std::bit_width(high) - 1;
    for (int i = 0; i < e; ++i) coder.encode(prefix_[axis][cls][std::min(i, kPrefixContexts - 1)], 1);
    coder.encode(prefix_[axis][cls][std::min(e, kPrefixContexts - 1)], 0);
    raw.write(high - (1u << e), e);
    raw.write(m & ((1u << k) - 1), k);
    update(axis, magnitude);
  }

  // False when the residual would not fit 32 bits.
  bool decode(ArithmeticDecoder& coder, BitReader& raw, int axis, int32_t& r) {
    const int cls = previous_[axis];
    if (!coder.decode(nonzero_[axis][cls])) {
      r = 0;
      update(axis, 0);
      return true;
    }
    const bool negative = raw.read_bit();
    const int k = order(axis);
    int e = 0;
    while (coder.decode(prefix_[axis][cls][std::min(e, kPrefixContexts - 1)]))
      if (++e + k > kMaxPrefix) return false;
    const uint32_t high = (1u << e) + raw.read(e);
    const uint32_t magnitude = (((high - 1) << k) | raw.read(k)) + 1;
    r = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
    update(axis, magnitude);
    return true;
  }

 private:
  // k from the running mean of magnitudes (sum_ ≈ 16 × mean).
  int order(int axis) const {
    const int bits = std::bit_width(sum_[axis] >> 4);
    return bits > 2 ? bits - 2 : 0;
  }
  void update(int axis, uint32_t magnitude) {
    previous_[axis] = magnitude == 0 ? 0 : magnitude <= 2 ? 1 : 2;
    sum_[axis] += std::min<uint32_t>(magnitude, 1u << 20) - (sum_[axis] >> 4);
  }

  BinContext nonzero_[3][kClasses];
  BinContext prefix_[3][kClasses][kPrefixContexts];
  int previous_[3] = {0, 0, 0};
  uint32_t sum_[3] = {0, 0, 0};
};

}  // namespace m4mesh
