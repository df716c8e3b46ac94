// Adaptive binary arithmetic coding: a range coder with adaptive
// probabilities (docs/container3d.md, "Contexts"). Integer arithmetic only, so every platform decodes the same
// bins. (Equiprobable bits are cheaper as raw bits beside it.)
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace m4mesh {

// The probability that the next bin is 0, in 1/32768, and the bins coded
// with it. A bin moves p0 by 1/8 of the way over a context's first 16
// bins, slowing to 1/64 from its 49th.
struct BinContext {
  uint16_t p0 = 1u << 14;
  uint16_t bins = 0;
};

namespace arithmetic {

inline constexpr uint32_t kTop = 1u << 24;
// The shift after n bins is min(kFirstShift + n / kShiftEvery, kLastShift).
inline constexpr int kFirstShift = 3;
inline constexpr int kShiftEvery = 16;
inline constexpr int kLastShift = 6;
inline constexpr uint16_t kWarmedUp = kShiftEvery * (kLastShift - kFirstShift);
// p0 stays within [kLowest, 32768 − kLowest], so that either
// sub-range of a range ≥ 2^24 is ≥ 2^16 and one byte renormalizes it.
inline constexpr uint32_t kLowest = 128;

// The lower (bin 0) sub-range's size.
inline uint32_t bound(uint32_t range, const BinContext& context) { return (range >> 15) * context.p0; }

// The count stops at kWarmedUp, where the shift reaches kLastShift; a 0
// only raises p0 and a 1 only lowers it, so each needs one bound.
static_assert(kFirstShift + kWarmedUp / kShiftEvery == kLastShift);
inline void adapt(BinContext& context, int bin) {
  const int shift = kFirstShift + context.bins / kShiftEvery;
  const uint32_t p0 = context.p0;
  const uint32_t raised = std::min(p0 + ((32768 - p0) >> shift), 32768 - kLowest), lowered = std::max(p0 - (p0 >> shift), kLowest);
  context.p0 = static_cast<uint16_t>(bin == 0 ? raised : lowered);
  context.bins = static_cast<uint16_t>(context.bins + (context.bins < kWarmedUp));
}

}  // namespace arithmetic

class ArithmeticEncoder {
 public:
  void encode(BinContext& context, int bin) {
    const uint32_t bound = arithmetic::bound(range_, context);
    if (bin == 0) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    arithmetic::adapt(context, bin);
    while (range_ < arithmetic::kTop) {
      range_ <<= 8;
      shift_low();
    }
  }
  std::vector<uint8_t> finish();

 private:
  void shift_low();

  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  std::vector<uint8_t> out_;
};

class ArithmeticDecoder {
 public:
  explicit ArithmeticDecoder(std::span<const uint8_t> data) : data_(data) {
    for (int i = 0; i < 5; ++i) code_ = (code_ << 8) | next_byte();
  }

  [[gnu::always_inline]] int decode(BinContext& context) {
    const uint32_t bound = arithmetic::bound(range_, context);
    int bin;
    if (code_ < bound) {
      range_ = bound;
      bin = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      bin = 1;
    }
    arithmetic::adapt(context, bin);
    // One byte always restores range_ ≥ 2^24: both sub-ranges keep at least
    // 128/32768 of a range ≥ 2^24.
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
  size_t position_ = 0;
  uint64_t overrun_ = 0;
  uint32_t code_ = 0;
  uint32_t range_ = 0xFFFFFFFF;
};

}  // namespace m4mesh
