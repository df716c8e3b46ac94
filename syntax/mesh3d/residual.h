// Adaptive binarization of signed residuals shared by the 3D codecs, one
// description for both directions: per channel (a coordinate axis, a
// matrix element, ...) a zero flag, then exp-Golomb bins with adaptive
// contexts and an adaptive order. The IO is syntax/mesh3d/entropy_io.h's.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>

#include "bitstream/arithmetic.h"
#include "common/error.h"

namespace m4mesh::syntax {

// The names a residual's symbols are traced and reported under.
struct ResidualNames {
  const char* nonzero;
  const char* prefix;
  const char* element;  // the residual as a whole, for errors
  const char* sign;     // the sign's bin, the suffix's top bin and its other bits
  const char* top;
  const char* suffix;
};

// A family's names from its stem (motion: motion_nonzero, motion_prefix, …)
// and the name of the residual as a whole.
#define M4MESH_RESIDUAL_NAMES(stem, element)                                                                                        \
  ResidualNames { stem "_nonzero", stem "_prefix", element, stem "_sign", stem "_top", stem "_suffix" }

// A zero flag, then |r| − 1 in exp-Golomb of order k, where k follows a
// running mean of the channel's magnitudes. The zero flag and the prefix
// bins are arithmetic-coded with contexts per channel and class of the
// channel's previous residual (0: zero, 1: prefix length e = 0, 2: e > 0),
// a class known as soon as that residual's bins are decoded. The sign is a
// bin by the sign of the channel's previous nonzero residual and the e + k
// suffix bits' top bit a bin by channel (both lean: prediction errors keep
// their sign along a surface, and magnitudes fall within a prefix's range),
// the other suffix bits raw.
template <int kChannels>
class ResidualCoder {
 public:
  static constexpr int kClasses = 3;
  static constexpr int kPrefixContexts = 12;
  static constexpr int kMaxPrefix = 30;  // |r| < 2^31

  // Trace context numbers: nonzero (channel · 3 + class) · 13, prefix bin i
  // the same + 1 + min(i, 11); sign channel · 3 + previous sign (0: none
  // yet, 1: positive, 2: negative); top channel.
  template <class IO>
  void describe(IO& io, int channel, int32_t& r, const ResidualNames& names) {
    const int cls = previous_[channel];
    const int context = (channel * kClasses + cls) * (kPrefixContexts + 1);
    bool nonzero = false;
    if constexpr (!IO::kReading) nonzero = r != 0;
    io.bin(names.nonzero, nonzero_[channel][cls], context, nonzero);
    if (!nonzero) {
      r = 0;
      update(channel, 0, 0);
      return;
    }
    const int k = order(channel);
    uint32_t magnitude = 0, m = 0, high = 0;
    int e = 0;
    if constexpr (!IO::kReading) {
      magnitude = static_cast<uint32_t>(r < 0 ? -static_cast<int64_t>(r) : r);
      m = magnitude - 1;
      high = (m >> k) + 1;  // ≥ 1
      e = std::bit_width(high) - 1;
    }
    // e bins '1', then a bin '0'.
    for (int i = 0;; ++i) {
      bool one = i < e;
      const int slot = std::min(i, kPrefixContexts - 1);
      io.bin(names.prefix, prefix_[channel][cls][slot], context + 1 + slot, one);
      if (!one) {
        e = i;
        break;
      }
      if (i + 1 + k > kMaxPrefix) io.fail(ErrorKind::kInvalidCode, names.element, "a residual longer than 32 bits");
    }
    // The sign (1: negative), then the suffix: e bits of h − 2^e and k bits
    // of m mod 2^k, at most 30 bits.
    const int n = e + k;
    bool negative = false;
    uint32_t suffix = 0;
    if constexpr (!IO::kReading) {
      negative = r < 0;
      suffix = ((high - (1u << e)) << k) | (m & ((1u << k) - 1));
    }
    const int sign_class = previous_sign_[channel];
    io.bin(names.sign, sign_[channel][sign_class], channel * 3 + sign_class, negative);
    previous_sign_[channel] = negative ? 2 : 1;
    if (n > 0) {
      bool top = suffix >> (n - 1) != 0;
      io.bin(names.top, top_[channel], channel, top);
      uint32_t low = suffix & ((1u << (n - 1)) - 1);
      if (n > 1) io.raw(names.suffix, n - 1, low);
      suffix = (top ? 1u << (n - 1) : 0u) | low;
    }
    if constexpr (IO::kReading) {
      magnitude = (((1u << e) - 1) << k) + suffix + 1;
      r = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
    }
    update(channel, magnitude, e + 1);
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
  BinContext sign_[kChannels][3];
  BinContext top_[kChannels];
  int previous_[kChannels] = {};
  int previous_sign_[kChannels] = {};
  uint32_t sum_[kChannels] = {};
};

}  // namespace m4mesh::syntax
