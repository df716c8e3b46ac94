// Little-endian fields of the binary sequence files (.m4seq, PC2, PLY),
// written byte by byte.
#pragma once

#include <cstdint>
#include <string>

#include "common/bit_cast.h"

namespace m4mesh {

inline void put_u32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}
inline void put_f32(std::string& out, float f) { put_u32(out, bit_cast<uint32_t>(f)); }

}  // namespace m4mesh
