// Several MD5 digests at once, one message a SIMD lane (natively
// AVX-512's sixteen or AVX2's eight where the processor has them, else
// SSE2's four; WebAssembly SIMD128's
// four through Emscripten's SSE2 headers), for messages of one length: the
// frames a group hash unit covers. Each digest is the one Md5 gives;
// without SIMD the messages are hashed one after the other.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace m4mesh {

// The most messages hashed side by side: a caller's batch that uses every lane.
inline constexpr size_t kMd5Batch = 16;

// out[k] = MD5 of messages[k][0 … length − 1], for every k (any count).
void md5_of_equal_lengths(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out);

}  // namespace m4mesh
