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

// A zero flag, then |r| − 1 in exp-Golomb of order k, where k follows a
// running mean of the channel's magnitudes. The zero flag and the prefix
// bins are arithmetic-coded with contexts per channel and class of the
// channel's previous residual (0: zero, 1: prefix length e = 0, 2: e > 0),
// a class known as soon as that residual's bins are decoded. The sign and
// the e + k suffix bits, equiprobable, are raw bits.
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
      update(channel, 0, 0);
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
    update(channel, magnitude, e + 1);
  }

  // False when the residual would not fit 32 bits.
  bool decode(ArithmeticDecoder& coder, BitReader& raw, int channel, int32_t& r) {
    const int cls = previous_[channel];
    if (!coder.decode(nonzero_[channel][cls])) {
      r = 0;
      update(channel, 0, 0);
      return true;
    }
    const int k = order(channel);
    int e = 0;
    while (coder.decode(prefix_[channel][cls][std::min(e, kPrefixContexts - 1)]))
      if (++e + k > kMaxPrefix) return false;
    // The sign, then the e + k suffix bits: at most 31 bits.
    const uint32_t bits = raw.read(1 + e + k);
    const uint32_t suffix = bits & ((1u << (e + k)) - 1);
    const uint32_t magnitude = (((1u << e) - 1) << k) + suffix + 1;
    r = bits >> (e + k) ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
    update(channel, magnitude, e + 1);
    return true;
  }

 private:
  // k ≈ log2 of 7/8 of the mean magnitude (sum_ ≈ 16 × mean): residuals
  // mostly need one or two prefix bins.
  int order(int channel) const {
    const int bits = std::bit_width((7 * sum_[channel]) >> 7);
    return bits > 1 ? bits - 1 : 0;
  }
  // symbol: 0 for a zero residual, else e + 1.
  void update(int channel, uint32_t magnitude, int symbol) {
    previous_[channel] = std::min(symbol, kClasses - 1);
    sum_[channel] += std::min<uint32_t>(magnitude, 1u << 20) - (sum_[channel] >> 4);
  }

  BinContext nonzero_[kChannels][kClasses];
  BinContext prefix_[kChannels][kClasses][kPrefixContexts];
  int previous_[kChannels] = {};
  uint32_t sum_[kChannels] = {};
};

}  // namespace m4mesh
