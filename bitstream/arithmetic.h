// Adaptive binary arithmetic coding: a range coder with adaptive
// probabilities, in one of two adaptations (docs/container3d.md,
// "Contexts"). Integer arithmetic only, so every platform decodes the same
// bins. (Equiprobable bits are cheaper as raw bits beside it.)
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace m4mesh {

// How a context's probability follows its bins.
enum class Adaptation : uint8_t {
  kFixedRate,  // 11-bit probabilities, each bin moves p0 by 1/32 of the way (3D versions 1 and 2)
  kWarmUp,     // 15-bit probabilities, moved by 1/8 over a context's first 16 bins, slowing to 1/64 from its 49th (version 3)
};

// The probability that the next bin is 0, in 1/32768, and the bins coded
// with it. Under kFixedRate p0 is the 11-bit probability times 16.
struct BinContext {
  uint16_t p0 = 1u << 14;
  uint16_t bins = 0;
};

namespace arithmetic {

inline constexpr uint32_t kTop = 1u << 24;
// Warm-up: the shift after n bins is min(kFirstShift + n / kShiftEvery, kLastShift).
inline constexpr int kFirstShift = 3;
inline constexpr int kShiftEvery = 16;
inline constexpr int kLastShift = 6;
inline constexpr uint16_t kWarmedUp = kShiftEvery * (kLastShift - kFirstShift);
// Warm-up: p0 stays within [kLowest, 32768 − kLowest], so that either
// sub-range of a range ≥ 2^24 is ≥ 2^16 and one byte renormalizes it.
inline constexpr uint32_t kLowest = 128;

// The lower (bin 0) sub-range's size.
inline uint32_t bound(uint32_t range, const BinContext& context, Adaptation adaptation) {
  return adaptation == Adaptation::kFixedRate ? (range >> 11) * (context.p0 >> 4u) : (range >> 15) * context.p0;
}

inline void adapt(BinContext& context, int bin, Adaptation adaptation) {
  uint32_t p0 = context.p0;
  if (adaptation == Adaptation::kFixedRate) {
    // In 11-bit terms: p0 += (2048 − p0) >> 5, or p0 −= p0 >> 5.
    p0 = bin == 0 ? p0 + (((32768 - p0) >> 9) << 4) : p0 - ((p0 >> 9) << 4);
  } else {
    const int shift = std::min(kFirstShift + context.bins / kShiftEvery, kLastShift);
    p0 = bin == 0 ? p0 + ((32768 - p0) >> shift) : p0 - (p0 >> shift);
    p0 = std::clamp(p0, kLowest, 32768 - kLowest);
    if (context.bins < kWarmedUp) ++context.bins;
  }
  context.p0 = static_cast<uint16_t>(p0);
}

}  // namespace arithmetic

class ArithmeticEncoder {
 public:
  explicit ArithmeticEncoder(Adaptation adaptation) : adaptation_(adaptation) {}

  void encode(BinContext& context, int bin) {
    const uint32_t bound = arithmetic::bound(range_, context, adaptation_);
    if (bin == 0) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    arithmetic::adapt(context, bin, adaptation_);
    while (range_ < arithmetic::kTop) {
      range_ <<= 8;
      shift_low();
    }
  }
  std::vector<uint8_t> finish();

 private:
  void shift_low();

  Adaptation adaptation_;
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  std::vector<uint8_t> out_;
};

class ArithmeticDecoder {
 public:
  ArithmeticDecoder(std::span<const uint8_t> data, Adaptation adaptation) : data_(data), adaptation_(adaptation) {
    for (int i = 0; i < 5; ++i) code_ = (code_ << 8) | next_byte();
  }

  int decode(BinContext& context) {
    const uint32_t bound = arithmetic::bound(range_, context, adaptation_);
    int bin;
    if (code_ < bound) {
      range_ = bound;
      bin = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      bin = 1;
    }
    arithmetic::adapt(context, bin, adaptation_);
    // One byte always restores range_ ≥ 2^24: both sub-ranges keep at least
    // 31/2048 (fixed rate) or 128/32768 (warm-up) of a range ≥ 2^24.
    if (range_ < arithmetic::kTop) {
      range_ <<= 8;
      code_ = (code_ << 8) | next_byte();
    }
    return bin;
  }

  // Bytes read past the end of the data (zeros were used): a sticky error.
  uint64_t overrun() const { return overrun_; }
  uint64_t position() const { return position_; }
  uint64_t size() const { return data_.size(); }

 private:
  uint32_t next_byte() {
    if (position_ < data_.size()) return data_[position_++];
    ++overrun_;
    return 0;
  }

  std::span<const uint8_t> data_;
  Adaptation adaptation_;
  size_t position_ = 0;
  uint64_t overrun_ = 0;
  uint32_t code_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
};

}  // namespace m4mesh
