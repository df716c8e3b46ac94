// Start codes (§2.1, §12) and next_start_code() stuffing (§2.2).
#pragma once

#include <cstdint>
#include <optional>

#include "bitstream/bit_reader.h"
#include "bitstream/bit_writer.h"

namespace m4mesh {

inline constexpr uint32_t kMeshObjectStartCode = 0x000001BC;
inline constexpr uint32_t kMeshObjectPlaneStartCode = 0x000001BD;
inline constexpr uint32_t kMeshObjectEndCode = 0x000001B1;
inline constexpr uint32_t kMesh3dObjectStartCode = 0x000001C4;
inline constexpr uint32_t kMesh3dUnitStartCode = 0x000001C5;

// Number of stuffing bits next_start_code() writes at this position (1…8).
inline int stuffing_bit_count(uint64_t position) { return 8 - static_cast<int>(position % 8); }

// The stuffing pattern of n bits: '0' followed by n-1 '1's.
inline uint32_t stuffing_pattern(int n) { return (1u << (n - 1)) - 1; }

void write_next_start_code(BitWriter& writer);

// nextbits_bytealigned(): the 32 bits at the current position rounded up to
// a byte boundary, or nothing when fewer than 32 bits remain there. Every
// plane ends with its own stuffing (§3.1), so the object loop calls it at
// an aligned position.
std::optional<uint32_t> nextbits_bytealigned(BitReader& reader);

}  // namespace m4mesh
