// Adaptive binarization of signed residuals shared by the 3D codecs: per
// channel (a coordinate axis, a matrix element, ...) a zero flag, then
// exp-Golomb bins with adaptive contexts and an adaptive order.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "bitstream/arithmetic.h"
#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"

namespace m4mesh {

// A zero flag per channel and class of the channel's previous residual,
// then |r| − 1 in exp-Golomb of order k, where k follows a running mean of
// the channel's magnitudes.
// The zero flag and the prefix bins are arithmetic-coded with adaptive
// contexts; the sign and the e + k suffix bits, equiprobable, are raw bits
// in the frame's raw section.
template <int kChannels>
class ResidualCoder {
 public:
  static constexpr int kClasses = 3;
  static constexpr int kPrefixContexts = 12;
  static constexpr int kMaxPrefix = 30;  // |r| < 2^31

  void encode(ArithmeticEncoder& coder, BitWriter& raw, int channel, int32_t r) {
    const int cls = previous_[channel];
    coder.encode(nonzero_[channel][cls], r != 0);
    if (r == 0) {
      update(channel, 0);
      return;
    }
    raw.write_bit(r < 0);
    const uint32_t magnitude = static_cast<uint32_t>(r < 0 ? -static_cast<int64_t>(r) : r);
    const int k = order(channel);
    const uint32_t m = magnitude - 1;
    const uint32_t high = (m >> k) + 1;  // ≥ 1
    const int e = std::bit_width(high) - 1;
    for (int i = 0; i < e; ++i) coder.encode(prefix_[channel][cls][std::min(i, kPrefixContexts - 1)], 1);
    coder.encode(prefix_[channel][cls][std::min(e, kPrefixContexts - 1)], 0);
    raw.write(high - (1u << e), e);
    raw.write(m & ((1u << k) - 1), k);
    update(channel, magnitude);
  }

  // False when the residual would not fit 32 bits.
  bool decode(ArithmeticDecoder& coder, BitReader& raw, int channel, int32_t& r) {
    const int cls = previous_[channel];
    if (!coder.decode(nonzero_[channel][cls])) {
      r = 0;
      update(channel, 0);
      return true;
    }
    const bool negative = raw.read_bit();
    const int k = order(channel);
    int e = 0;
    while (coder.decode(prefix_[channel][cls][std::min(e, kPrefixContexts - 1)]))
      if (++e + k > kMaxPrefix) return false;
    const uint32_t high = (1u << e) + raw.read(e);
    const uint32_t magnitude = (((high - 1) << k) | raw.read(k)) + 1;
    r = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
    update(channel, magnitude);
    return true;
  }

 private:
  // k from the running mean of magnitudes (sum_ ≈ 16 × mean).
  int order(int channel) const {
    const int bits = std::bit_width(sum_[channel] >> 4);
    return bits > 2 ? bits - 2 : 0;
  }
  void update(int channel, uint32_t magnitude) {
    previous_[channel] = magnitude == 0 ? 0 : magnitude <= 2 ? 1 : 2;
    sum_[channel] += std::min<uint32_t>(magnitude, 1u << 20) - (sum_[channel] >> 4);
  }

  BinContext nonzero_[kChannels][kClasses];
  BinContext prefix_[kChannels][kClasses][kPrefixContexts];
  int previous_[kChannels] = {};
  uint32_t sum_[kChannels] = {};
};

}  // namespace m4mesh
