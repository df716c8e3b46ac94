#include "bitstream/bit_reader.h"

namespace m4mesh {

void BitReader::refill_near_end() {
  while (cache_bits_ <= 56) {
    const uint64_t byte = consumed_bytes_ < size_ ? data_[consumed_bytes_] : 0;
    cache_ |= byte << (56 - cache_bits_);
    cache_bits_ += 8;
    ++consumed_bytes_;
  }
}

void BitReader::seek(uint64_t bit_position) {
  consumed_bytes_ = static_cast<size_t>(bit_position / 8);
  cache_ = 0;
  cache_bits_ = 0;
  refill();
  skip(static_cast<int>(bit_position % 8));
}

}  // namespace m4mesh
