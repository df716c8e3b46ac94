// Several MD5 digests at once, one message a SIMD lane (SSE2 natively,
// WebAssembly SIMD128 through Emscripten's SSE2 headers), for messages of
// one length: the frames a group hash unit covers. Each digest is the one
// Md5 gives; without SIMD the messages are hashed one after the other.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace m4mesh {

inline constexpr size_t kMd5Lanes = 4;

// out[k] = MD5 of messages[k][0 … length − 1], for every k (any count).
void md5_of_equal_lengths(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out);

}  // namespace m4mesh
