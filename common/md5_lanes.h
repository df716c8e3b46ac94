// Several MD5 digests at once, one message a SIMD lane (natively
// AVX-512's sixteen or AVX2's eight where the processor has them, else
// SSE2's sixteen, eight or four in as many vectors of four; WebAssembly
// SIMD128's the same through Emscripten's SSE2 headers), for messages of
// one length: the frames a group hash unit covers. Each digest is the one
// Md5 gives; without SIMD the messages are hashed one after the other.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace m4mesh {

// The most messages hashed side by side: a caller's batch that uses every lane.
inline constexpr size_t kMd5Batch = 16;

// out[k] = MD5 of messages[k][0 … length − 1], for every k (any count),
// in vectors of at most `widest_bits` (512, 256, 128; 0: one by one), so
// that tests take every path on one processor.
void md5_of_equal_lengths(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out,
                          int widest_bits = 512);

}  // namespace m4mesh
