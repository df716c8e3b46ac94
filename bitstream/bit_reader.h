// MSB-first bit reader with a 64-bit cache. Reading past the end yields
// zero bits and makes overrun() true for good (a sticky error): callers
// check it once per syntax element instead of after every refill.
#pragma once

#include <cstddef>
#include <cstdint>

namespace m4mesh {

class BitReader {
 public:
  BitReader(const uint8_t* data, size_t size) : data_(data), size_(size) { refill(); }

  const uint8_t* data() const { return data_; }
  // Bits consumed so far (may exceed size_bits() after an overrun).
  uint64_t position() const { return consumed_bytes_ * 8 - cache_bits_; }
  uint64_t size_bits() const { return static_cast<uint64_t>(size_) * 8; }
  uint64_t bits_left() const { return overrun() ? 0 : size_bits() - position(); }
  bool overrun() const { return position() > size_bits(); }
  bool byte_aligned() const { return position() % 8 == 0; }

  // The next n bits (0 ≤ n ≤ 32) without consuming them.
  uint32_t peek(int n) {
    if (n == 0) return 0;
    if (cache_bits_ < n) refill();
    return static_cast<uint32_t>(cache_ >> (64 - n));
  }
  void skip(int n) {
    if (cache_bits_ < n) refill();
    cache_ <<= n;
    cache_bits_ -= n;
  }
  uint32_t read(int n) {
    if (cache_bits_ < n) refill();
    const uint32_t value = static_cast<uint32_t>((cache_ >> 1) >> (63 - n));  // n = 0 gives 0
    cache_ <<= n;
    cache_bits_ -= n;
    return value;
  }
  bool read_bit() { return read(1) != 0; }

  // Moves to an absolute bit position (≤ size_bits()).
  void seek(uint64_t bit_position);

 private:
  // Fills the cache to at least 57 bits: eight bytes at once away from the
  // end (bits past the counted bytes are the stream's next bits, so ORing
  // them again later changes nothing), else one byte at a time.
  void refill() {
    if (consumed_bytes_ + 8 <= size_) {
      const uint8_t* p = data_ + consumed_bytes_;
      const uint64_t word = uint64_t{p[0]} << 56 | uint64_t{p[1]} << 48 | uint64_t{p[2]} << 40 | uint64_t{p[3]} << 32 |
                            uint64_t{p[4]} << 24 | uint64_t{p[5]} << 16 | uint64_t{p[6]} << 8 | p[7];
      cache_ |= word >> cache_bits_;
      const int bytes = (63 - cache_bits_) >> 3;
      consumed_bytes_ += static_cast<size_t>(bytes);
      cache_bits_ += 8 * bytes;
      return;
    }
    refill_near_end();
  }
  void refill_near_end();

  const uint8_t* data_;
  size_t size_;
  size_t consumed_bytes_ = 0;  // bytes moved into the cache (or zero-filled past the end)
  uint64_t cache_ = 0;         // next bits, left-aligned
  int cache_bits_ = 0;
};

}  // namespace m4mesh
