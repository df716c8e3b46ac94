// MSB-first bit writer into a byte vector (never host memory layout).
#pragma once

#include <cstdint>
#include <vector>

namespace m4mesh {

class BitWriter {
 public:
  // Writes the low n bits of value (0 ≤ n ≤ 32), most significant first.
  void write(uint32_t value, int n) {
    if (n == 0) return;
    accumulator_ = (accumulator_ << n) | (value & mask(n));
    pending_bits_ += n;
    while (pending_bits_ >= 8) {
      pending_bits_ -= 8;
      bytes_.push_back(static_cast<uint8_t>(accumulator_ >> pending_bits_));
    }
  }
  void write_bit(bool bit) { write(bit ? 1u : 0u, 1); }

  uint64_t position() const { return bytes_.size() * 8 + static_cast<uint64_t>(pending_bits_); }
  bool byte_aligned() const { return pending_bits_ == 0; }

  // The bytes written; the position must be byte-aligned.
  const std::vector<uint8_t>& bytes() const;
  std::vector<uint8_t> take_bytes();

 private:
  static uint64_t mask(int n) { return (uint64_t{1} << n) - 1; }

  std::vector<uint8_t> bytes_;
  uint64_t accumulator_ = 0;
  int pending_bits_ = 0;
};

}  // namespace m4mesh
