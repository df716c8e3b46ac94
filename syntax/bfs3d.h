// bfs3d (codec_id 1) syntax: the codec header that follows the object
// header, and the binarization of motion residuals (docs/codec_bfs3d.md).
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "bitstream/arithmetic.h"
#include "syntax/io.h"

namespace m4mesh {

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

// Adaptive contexts of the residual binarization: a zero flag, a sign, and
// an order-0 exp-Golomb prefix, each per coordinate and per class of the
// previous residual of that coordinate; the suffix bits are bypass bits.
class ResidualModel {
 public:
  static constexpr int kClasses = 3;
  static constexpr int kPrefixContexts = 12;
  static constexpr int kMaxPrefix = 30;  // |r| < 2^31

  void encode(ArithmeticEncoder& coder, int axis, int32_t r) {
    const int cls = previous_[axis];
    coder.encode(nonzero_[axis][cls], r != 0);
    previous_[axis] = class_of(r);
    if (r == 0) return;
    coder.encode(sign_[axis], r < 0);
    const uint32_t magnitude = static_cast<uint32_t>(r < 0 ? -static_cast<int64_t>(r) : r);  // ≥ 1
    const int e = std::bit_width(magnitude) - 1;
    for (int i = 0; i < e; ++i) coder.encode(prefix_[axis][cls][std::min(i, kPrefixContexts - 1)], 1);
    coder.encode(prefix_[axis][cls][std::min(e, kPrefixContexts - 1)], 0);
    coder.encode_bypass(magnitude - (1u << e), e);
  }

  // False when the prefix is longer than any 32-bit residual needs.
  bool decode(ArithmeticDecoder& coder, int axis, int32_t& r) {
    const int cls = previous_[axis];
    if (!coder.decode(nonzero_[axis][cls])) {
      r = 0;
      previous_[axis] = 0;
      return true;
    }
    const bool negative = coder.decode(sign_[axis]);
    int e = 0;
    while (coder.decode(prefix_[axis][cls][std::min(e, kPrefixContexts - 1)])) {
      if (++e > kMaxPrefix) return false;
    }
    const uint32_t magnitude = (1u << e) + coder.decode_bypass(e);
    r = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
    previous_[axis] = class_of(r);
    return true;
  }

 private:
  static int class_of(int32_t r) { return r == 0 ? 0 : (r >= -2 && r <= 2) ? 1 : 2; }

  BinContext nonzero_[3][kClasses];
  BinContext sign_[3];
  BinContext prefix_[3][kClasses][kPrefixContexts];
  int previous_[3] = {0, 0, 0};
};

}  // namespace m4mesh
