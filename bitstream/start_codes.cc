#include "bitstream/start_codes.h"

namespace m4mesh {

void write_next_start_code(BitWriter& writer) {
  int n = stuffing_bit_count(writer.position());
  writer.write(stuffing_pattern(n), n);
}

std::optional<uint32_t> nextbits_bytealigned(BitReader& reader) {
  uint64_t saved = reader.position();
  uint64_t aligned = (saved + 7) / 8 * 8;
  if (aligned + 32 > reader.size_bits()) return std::nullopt;
  reader.seek(aligned);
  uint32_t value = reader.read(32);
  reader.seek(saved);
  return value;
}

}  // namespace m4mesh
