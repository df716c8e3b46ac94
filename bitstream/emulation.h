// Emulation prevention for 3D container payloads (§12): a payload never
// holds 0x000001, so start codes can be found by scanning.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace m4mesh {

// Inserts 0x03 after every two 0x00 bytes that a byte ≤ 0x03, or the end of
// the payload, follows.
std::vector<uint8_t> escape_payload(std::span<const uint8_t> payload);

// Removes every 0x03 that follows two 0x00 bytes.
std::vector<uint8_t> unescape_payload(std::span<const uint8_t> escaped);

}  // namespace m4mesh
