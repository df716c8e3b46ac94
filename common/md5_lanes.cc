#include "common/md5_lanes.h"

#include <cstring>

#include "common/md5.h"

#if !defined(M4MESH_NO_SIMD) && (defined(__SSE2__) || defined(__wasm_simd128__))
#include <emmintrin.h>
#define M4MESH_MD5_LANES 1
#endif

namespace m4mesh {

namespace {

void one_by_one(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out) {
  for (size_t k = 0; k < messages.size(); ++k) {
    Md5 md5;
    md5.update(messages[k], length);
    out[k] = md5.digest();
  }
}

#ifdef M4MESH_MD5_LANES

// RFC 1321's round functions on four lanes.
inline __m128i F(__m128i b, __m128i c, __m128i d) { return _mm_xor_si128(d, _mm_and_si128(b, _mm_xor_si128(c, d))); }
inline __m128i G(__m128i b, __m128i c, __m128i d) { return _mm_xor_si128(c, _mm_and_si128(d, _mm_xor_si128(b, c))); }
inline __m128i H(__m128i b, __m128i c, __m128i d) { return _mm_xor_si128(b, _mm_xor_si128(c, d)); }
inline __m128i I(__m128i b, __m128i c, __m128i d) { return _mm_xor_si128(c, _mm_or_si128(b, _mm_xor_si128(d, _mm_set1_epi32(-1)))); }

// a = b + ((a + f(b, c, d) + word + constant) rotated left by s).
#define M4MESH_MD5_STEP(f, a, b, c, d, word, s, constant)                                                           \
  do {                                                                                                                \
    const __m128i sum = _mm_add_epi32(_mm_add_epi32(a, f(b, c, d)), _mm_add_epi32(word, _mm_set1_epi32(static_cast<int>(constant)))); \
    a = _mm_add_epi32(b, _mm_or_si128(_mm_slli_epi32(sum, s), _mm_srli_epi32(sum, 32 - (s))));                   \
  } while (false)

// One 64-byte block of each lane's message.
void blocks(__m128i state[4], const uint8_t* const lane[kMd5Lanes]) {
  __m128i w[16];
  for (int k = 0; k < 4; ++k) {
    const __m128i r0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[0] + 16 * k));
    const __m128i r1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[1] + 16 * k));
    const __m128i r2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[2] + 16 * k));
    const __m128i r3 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[3] + 16 * k));
    // Transposed: w[4k + j] holds word 4k + j of every lane (little-endian words, as RFC 1321 reads them).
    const __m128i t0 = _mm_unpacklo_epi32(r0, r1), t1 = _mm_unpacklo_epi32(r2, r3);
    const __m128i t2 = _mm_unpackhi_epi32(r0, r1), t3 = _mm_unpackhi_epi32(r2, r3);
    w[4 * k] = _mm_unpacklo_epi64(t0, t1);
    w[4 * k + 1] = _mm_unpackhi_epi64(t0, t1);
    w[4 * k + 2] = _mm_unpacklo_epi64(t2, t3);
    w[4 * k + 3] = _mm_unpackhi_epi64(t2, t3);
  }
  __m128i a = state[0], b = state[1], c = state[2], d = state[3];
  M4MESH_MD5_STEP(F, a, b, c, d, w[0], 7, 0xd76aa478u);
  M4MESH_MD5_STEP(F, d, a, b, c, w[1], 12, 0xe8c7b756u);
  M4MESH_MD5_STEP(F, c, d, a, b, w[2], 17, 0x242070dbu);
  M4MESH_MD5_STEP(F, b, c, d, a, w[3], 22, 0xc1bdceeeu);
  M4MESH_MD5_STEP(F, a, b, c, d, w[4], 7, 0xf57c0fafu);
  M4MESH_MD5_STEP(F, d, a, b, c, w[5], 12, 0x4787c62au);
  M4MESH_MD5_STEP(F, c, d, a, b, w[6], 17, 0xa8304613u);
  M4MESH_MD5_STEP(F, b, c, d, a, w[7], 22, 0xfd469501u);
  M4MESH_MD5_STEP(F, a, b, c, d, w[8], 7, 0x698098d8u);
  M4MESH_MD5_STEP(F, d, a, b, c, w[9], 12, 0x8b44f7afu);
  M4MESH_MD5_STEP(F, c, d, a, b, w[10], 17, 0xffff5bb1u);
  M4MESH_MD5_STEP(F, b, c, d, a, w[11], 22, 0x895cd7beu);
  M4MESH_MD5_STEP(F, a, b, c, d, w[12], 7, 0x6b901122u);
  M4MESH_MD5_STEP(F, d, a, b, c, w[13], 12, 0xfd987193u);
  M4MESH_MD5_STEP(F, c, d, a, b, w[14], 17, 0xa679438eu);
  M4MESH_MD5_STEP(F, b, c, d, a, w[15], 22, 0x49b40821u);
  M4MESH_MD5_STEP(G, a, b, c, d, w[1], 5, 0xf61e2562u);
  M4MESH_MD5_STEP(G, d, a, b, c, w[6], 9, 0xc040b340u);
  M4MESH_MD5_STEP(G, c, d, a, b, w[11], 14, 0x265e5a51u);
  M4MESH_MD5_STEP(G, b, c, d, a, w[0], 20, 0xe9b6c7aau);
  M4MESH_MD5_STEP(G, a, b, c, d, w[5], 5, 0xd62f105du);
  M4MESH_MD5_STEP(G, d, a, b, c, w[10], 9, 0x02441453u);
  M4MESH_MD5_STEP(G, c, d, a, b, w[15], 14, 0xd8a1e681u);
  M4MESH_MD5_STEP(G, b, c, d, a, w[4], 20, 0xe7d3fbc8u);
  M4MESH_MD5_STEP(G, a, b, c, d, w[9], 5, 0x21e1cde6u);
  M4MESH_MD5_STEP(G, d, a, b, c, w[14], 9, 0xc33707d6u);
  M4MESH_MD5_STEP(G, c, d, a, b, w[3], 14, 0xf4d50d87u);
  M4MESH_MD5_STEP(G, b, c, d, a, w[8], 20, 0x455a14edu);
  M4MESH_MD5_STEP(G, a, b, c, d, w[13], 5, 0xa9e3e905u);
  M4MESH_MD5_STEP(G, d, a, b, c, w[2], 9, 0xfcefa3f8u);
  M4MESH_MD5_STEP(G, c, d, a, b, w[7], 14, 0x676f02d9u);
  M4MESH_MD5_STEP(G, b, c, d, a, w[12], 20, 0x8d2a4c8au);
  M4MESH_MD5_STEP(H, a, b, c, d, w[5], 4, 0xfffa3942u);
  M4MESH_MD5_STEP(H, d, a, b, c, w[8], 11, 0x8771f681u);
  M4MESH_MD5_STEP(H, c, d, a, b, w[11], 16, 0x6d9d6122u);
  M4MESH_MD5_STEP(H, b, c, d, a, w[14], 23, 0xfde5380cu);
  M4MESH_MD5_STEP(H, a, b, c, d, w[1], 4, 0xa4beea44u);
  M4MESH_MD5_STEP(H, d, a, b, c, w[4], 11, 0x4bdecfa9u);
  M4MESH_MD5_STEP(H, c, d, a, b, w[7], 16, 0xf6bb4b60u);
  M4MESH_MD5_STEP(H, b, c, d, a, w[10], 23, 0xbebfbc70u);
  M4MESH_MD5_STEP(H, a, b, c, d, w[13], 4, 0x289b7ec6u);
  M4MESH_MD5_STEP(H, d, a, b, c, w[0], 11, 0xeaa127fau);
  M4MESH_MD5_STEP(H, c, d, a, b, w[3], 16, 0xd4ef3085u);
  M4MESH_MD5_STEP(H, b, c, d, a, w[6], 23, 0x04881d05u);
  M4MESH_MD5_STEP(H, a, b, c, d, w[9], 4, 0xd9d4d039u);
  M4MESH_MD5_STEP(H, d, a, b, c, w[12], 11, 0xe6db99e5u);
  M4MESH_MD5_STEP(H, c, d, a, b, w[15], 16, 0x1fa27cf8u);
  M4MESH_MD5_STEP(H, b, c, d, a, w[2], 23, 0xc4ac5665u);
  M4MESH_MD5_STEP(I, a, b, c, d, w[0], 6, 0xf4292244u);
  M4MESH_MD5_STEP(I, d, a, b, c, w[7], 10, 0x432aff97u);
  M4MESH_MD5_STEP(I, c, d, a, b, w[14], 15, 0xab9423a7u);
  M4MESH_MD5_STEP(I, b, c, d, a, w[5], 21, 0xfc93a039u);
  M4MESH_MD5_STEP(I, a, b, c, d, w[12], 6, 0x655b59c3u);
  M4MESH_MD5_STEP(I, d, a, b, c, w[3], 10, 0x8f0ccc92u);
  M4MESH_MD5_STEP(I, c, d, a, b, w[10], 15, 0xffeff47du);
  M4MESH_MD5_STEP(I, b, c, d, a, w[1], 21, 0x85845dd1u);
  M4MESH_MD5_STEP(I, a, b, c, d, w[8], 6, 0x6fa87e4fu);
  M4MESH_MD5_STEP(I, d, a, b, c, w[15], 10, 0xfe2ce6e0u);
  M4MESH_MD5_STEP(I, c, d, a, b, w[6], 15, 0xa3014314u);
  M4MESH_MD5_STEP(I, b, c, d, a, w[13], 21, 0x4e0811a1u);
  M4MESH_MD5_STEP(I, a, b, c, d, w[4], 6, 0xf7537e82u);
  M4MESH_MD5_STEP(I, d, a, b, c, w[11], 10, 0xbd3af235u);
  M4MESH_MD5_STEP(I, c, d, a, b, w[2], 15, 0x2ad7d2bbu);
  M4MESH_MD5_STEP(I, b, c, d, a, w[9], 21, 0xeb86d391u);
  state[0] = _mm_add_epi32(state[0], a);
  state[1] = _mm_add_epi32(state[1], b);
  state[2] = _mm_add_epi32(state[2], c);
  state[3] = _mm_add_epi32(state[3], d);
}

#undef M4MESH_MD5_STEP

// kMd5Lanes messages of `length` bytes.
void lanes(const uint8_t* const messages[kMd5Lanes], size_t length, std::array<uint8_t, 16>* out) {
  __m128i state[4] = {_mm_set1_epi32(0x67452301), _mm_set1_epi32(static_cast<int>(0xefcdab89u)), _mm_set1_epi32(static_cast<int>(0x98badcfeu)),
                      _mm_set1_epi32(0x10325476)};
  const size_t whole = length / 64;
  const uint8_t* at[kMd5Lanes];
  for (size_t b = 0; b < whole; ++b) {
    for (size_t l = 0; l < kMd5Lanes; ++l) at[l] = messages[l] + 64 * b;
    blocks(state, at);
  }
  // The tail, 0x80, zeros and the length in bits: one or two blocks, the same shape in every lane.
  const size_t tail = length % 64, padded = tail < 56 ? 64 : 128;
  alignas(16) uint8_t last[kMd5Lanes][128];
  const uint64_t bits = uint64_t{length} * 8;
  for (size_t l = 0; l < kMd5Lanes; ++l) {
    std::memset(last[l], 0, padded);
    std::memcpy(last[l], messages[l] + 64 * whole, tail);
    last[l][tail] = 0x80;
    for (int i = 0; i < 8; ++i) last[l][padded - 8 + static_cast<size_t>(i)] = static_cast<uint8_t>(bits >> (8 * i));
  }
  for (size_t b = 0; b < padded; b += 64) {
    for (size_t l = 0; l < kMd5Lanes; ++l) at[l] = last[l] + b;
    blocks(state, at);
  }
  alignas(16) uint32_t words[4][kMd5Lanes];
  for (int i = 0; i < 4; ++i) _mm_store_si128(reinterpret_cast<__m128i*>(words[i]), state[i]);
  for (size_t l = 0; l < kMd5Lanes; ++l)
    for (int i = 0; i < 4; ++i)
      for (int byte = 0; byte < 4; ++byte) out[l][static_cast<size_t>(4 * i + byte)] = static_cast<uint8_t>(words[i][l] >> (8 * byte));
}

#endif

}  // namespace

void md5_of_equal_lengths(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out) {
  size_t k = 0;
#ifdef M4MESH_MD5_LANES
  for (; k + kMd5Lanes <= messages.size(); k += kMd5Lanes) lanes(messages.data() + k, length, out.data() + k);
#endif
  one_by_one(messages.subspan(k), length, out.subspan(k));
}

}  // namespace m4mesh
