// Adaptive binary arithmetic coding: a range coder with 11-bit adaptive
// probabilities. Integer arithmetic only, so every platform decodes the
// same bins. (Equiprobable bits are cheaper as raw bits beside it.)
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace m4mesh {

// The probability that the next bin is 0, in 1/2048; adapts after each bin.
struct BinContext {
  uint16_t p0 = 1024;
};

class ArithmeticEncoder {
 public:
  void encode(BinContext& context, int bin) {
    const uint32_t bound = (range_ >> kProbabilityBits) * context.p0;
    if (bin == 0) {
      range_ = bound;
      context.p0 = static_cast<uint16_t>(context.p0 + ((kOne - context.p0) >> kAdaptShift));
    } else {
      low_ += bound;
      range_ -= bound;
      context.p0 = static_cast<uint16_t>(context.p0 - (context.p0 >> kAdaptShift));
    }
    while (range_ < kTop) {
      range_ <<= 8;
      shift_low();
    }
  }
  std::vector<uint8_t> finish();

  static constexpr int kProbabilityBits = 11;
  static constexpr uint32_t kOne = 1u << kProbabilityBits;
  static constexpr int kAdaptShift = 5;
  static constexpr uint32_t kTop = 1u << 24;

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

  int decode(BinContext& context) {
    const uint32_t p0 = context.p0;
    const uint32_t bound = (range_ >> ArithmeticEncoder::kProbabilityBits) * p0;
    int bin;
    if (code_ < bound) {
      range_ = bound;
      context.p0 = static_cast<uint16_t>(p0 + ((ArithmeticEncoder::kOne - p0) >> ArithmeticEncoder::kAdaptShift));
      bin = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      context.p0 = static_cast<uint16_t>(p0 - (p0 >> ArithmeticEncoder::kAdaptShift));
      bin = 1;
    }
    // One byte always restores range_ ≥ kTop: p0 stays within [31, 2017],
    // so both sub-ranges keep at least 31/2048 of a range ≥ 2^24.
    if (range_ < ArithmeticEncoder::kTop) {
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
