#include "bitstream/bit_reader.h"

namespace m4mesh {

void BitReader::seek(uint64_t bit_position) {
  consumed_bytes_ = static_cast<size_t>(bit_position / 8);
  cache_ = 0;
  cache_bits_ = 0;
  refill();
  skip(static_cast<int>(bit_position % 8));
}

}  // namespace m4mesh
