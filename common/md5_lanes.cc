#include "common/md5_lanes.h"

#include <cstring>

#include "common/cpu.h"
#include "common/md5.h"

#if !defined(M4MESH_NO_SIMD) && (defined(__SSE2__) || defined(__wasm_simd128__))
#include <emmintrin.h>
#define M4MESH_MD5_LANES 1
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#include <immintrin.h>
#define M4MESH_MD5_AVX2 1  // AVX2 and AVX-512, each chosen at run time where the processor has it
#endif
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

// RFC 1321's 64 steps, each STEP(f, a, b, c, d, word, shift, constant).
#define M4MESH_MD5_ROUNDS(STEP, F, G, H, I) \
  STEP(F, a, b, c, d, w[0], 7, 0xd76aa478u); \
  STEP(F, d, a, b, c, w[1], 12, 0xe8c7b756u); \
  STEP(F, c, d, a, b, w[2], 17, 0x242070dbu); \
  STEP(F, b, c, d, a, w[3], 22, 0xc1bdceeeu); \
  STEP(F, a, b, c, d, w[4], 7, 0xf57c0fafu); \
  STEP(F, d, a, b, c, w[5], 12, 0x4787c62au); \
  STEP(F, c, d, a, b, w[6], 17, 0xa8304613u); \
  STEP(F, b, c, d, a, w[7], 22, 0xfd469501u); \
  STEP(F, a, b, c, d, w[8], 7, 0x698098d8u); \
  STEP(F, d, a, b, c, w[9], 12, 0x8b44f7afu); \
  STEP(F, c, d, a, b, w[10], 17, 0xffff5bb1u); \
  STEP(F, b, c, d, a, w[11], 22, 0x895cd7beu); \
  STEP(F, a, b, c, d, w[12], 7, 0x6b901122u); \
  STEP(F, d, a, b, c, w[13], 12, 0xfd987193u); \
  STEP(F, c, d, a, b, w[14], 17, 0xa679438eu); \
  STEP(F, b, c, d, a, w[15], 22, 0x49b40821u); \
  STEP(G, a, b, c, d, w[1], 5, 0xf61e2562u); \
  STEP(G, d, a, b, c, w[6], 9, 0xc040b340u); \
  STEP(G, c, d, a, b, w[11], 14, 0x265e5a51u); \
  STEP(G, b, c, d, a, w[0], 20, 0xe9b6c7aau); \
  STEP(G, a, b, c, d, w[5], 5, 0xd62f105du); \
  STEP(G, d, a, b, c, w[10], 9, 0x02441453u); \
  STEP(G, c, d, a, b, w[15], 14, 0xd8a1e681u); \
  STEP(G, b, c, d, a, w[4], 20, 0xe7d3fbc8u); \
  STEP(G, a, b, c, d, w[9], 5, 0x21e1cde6u); \
  STEP(G, d, a, b, c, w[14], 9, 0xc33707d6u); \
  STEP(G, c, d, a, b, w[3], 14, 0xf4d50d87u); \
  STEP(G, b, c, d, a, w[8], 20, 0x455a14edu); \
  STEP(G, a, b, c, d, w[13], 5, 0xa9e3e905u); \
  STEP(G, d, a, b, c, w[2], 9, 0xfcefa3f8u); \
  STEP(G, c, d, a, b, w[7], 14, 0x676f02d9u); \
  STEP(G, b, c, d, a, w[12], 20, 0x8d2a4c8au); \
  STEP(H, a, b, c, d, w[5], 4, 0xfffa3942u); \
  STEP(H, d, a, b, c, w[8], 11, 0x8771f681u); \
  STEP(H, c, d, a, b, w[11], 16, 0x6d9d6122u); \
  STEP(H, b, c, d, a, w[14], 23, 0xfde5380cu); \
  STEP(H, a, b, c, d, w[1], 4, 0xa4beea44u); \
  STEP(H, d, a, b, c, w[4], 11, 0x4bdecfa9u); \
  STEP(H, c, d, a, b, w[7], 16, 0xf6bb4b60u); \
  STEP(H, b, c, d, a, w[10], 23, 0xbebfbc70u); \
  STEP(H, a, b, c, d, w[13], 4, 0x289b7ec6u); \
  STEP(H, d, a, b, c, w[0], 11, 0xeaa127fau); \
  STEP(H, c, d, a, b, w[3], 16, 0xd4ef3085u); \
  STEP(H, b, c, d, a, w[6], 23, 0x04881d05u); \
  STEP(H, a, b, c, d, w[9], 4, 0xd9d4d039u); \
  STEP(H, d, a, b, c, w[12], 11, 0xe6db99e5u); \
  STEP(H, c, d, a, b, w[15], 16, 0x1fa27cf8u); \
  STEP(H, b, c, d, a, w[2], 23, 0xc4ac5665u); \
  STEP(I, a, b, c, d, w[0], 6, 0xf4292244u); \
  STEP(I, d, a, b, c, w[7], 10, 0x432aff97u); \
  STEP(I, c, d, a, b, w[14], 15, 0xab9423a7u); \
  STEP(I, b, c, d, a, w[5], 21, 0xfc93a039u); \
  STEP(I, a, b, c, d, w[12], 6, 0x655b59c3u); \
  STEP(I, d, a, b, c, w[3], 10, 0x8f0ccc92u); \
  STEP(I, c, d, a, b, w[10], 15, 0xffeff47du); \
  STEP(I, b, c, d, a, w[1], 21, 0x85845dd1u); \
  STEP(I, a, b, c, d, w[8], 6, 0x6fa87e4fu); \
  STEP(I, d, a, b, c, w[15], 10, 0xfe2ce6e0u); \
  STEP(I, c, d, a, b, w[6], 15, 0xa3014314u); \
  STEP(I, b, c, d, a, w[13], 21, 0x4e0811a1u); \
  STEP(I, a, b, c, d, w[4], 6, 0xf7537e82u); \
  STEP(I, d, a, b, c, w[11], 10, 0xbd3af235u); \
  STEP(I, c, d, a, b, w[2], 15, 0x2ad7d2bbu); \
  STEP(I, b, c, d, a, w[9], 21, 0xeb86d391u);

// The state of N lanes: word i of lane l at state[i][l].
template <size_t N>
using LaneState = uint32_t[4][N];

// Words 4k … 4k + 3 of four lanes, transposed: out[j] holds word 4k + j of every lane (little-endian words, as
// RFC 1321 reads them).
inline void transpose4(const uint8_t* const lane[4], int k, __m128i out[4]) {
  const __m128i r0 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[0] + 16 * k));
  const __m128i r1 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[1] + 16 * k));
  const __m128i r2 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[2] + 16 * k));
  const __m128i r3 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(lane[3] + 16 * k));
  const __m128i t0 = _mm_unpacklo_epi32(r0, r1), t1 = _mm_unpacklo_epi32(r2, r3);
  const __m128i t2 = _mm_unpackhi_epi32(r0, r1), t3 = _mm_unpackhi_epi32(r2, r3);
  out[0] = _mm_unpacklo_epi64(t0, t1);
  out[1] = _mm_unpackhi_epi64(t0, t1);
  out[2] = _mm_unpacklo_epi64(t2, t3);
  out[3] = _mm_unpackhi_epi64(t2, t3);
}

// RFC 1321's round functions and step on any width's lanes, through the
// width's operations M4MESH_V_XOR, _AND, _OR, _ADD, _SET1, _SLL and _SRL.
#define M4MESH_F(b, c, d) M4MESH_V_XOR(d, M4MESH_V_AND(b, M4MESH_V_XOR(c, d)))
#define M4MESH_G(b, c, d) M4MESH_V_XOR(c, M4MESH_V_AND(d, M4MESH_V_XOR(b, c)))
#define M4MESH_H(b, c, d) M4MESH_V_XOR(b, M4MESH_V_XOR(c, d))
#define M4MESH_I(b, c, d) M4MESH_V_XOR(c, M4MESH_V_OR(b, M4MESH_V_XOR(d, M4MESH_V_SET1(-1))))
// a = b + ((a + f(b, c, d) + word + constant) rotated left by s).
#define M4MESH_STEP(f, a, b, c, d, word, s, constant)                                                                   \
  do {                                                                                                                  \
    const auto sum = M4MESH_V_ADD(M4MESH_V_ADD(a, f(b, c, d)), M4MESH_V_ADD(word, M4MESH_V_SET1(static_cast<int>(constant)))); \
    a = M4MESH_V_ADD(b, M4MESH_V_OR(M4MESH_V_SLL(sum, s), M4MESH_V_SRL(sum, 32 - (s))));                               \
  } while (false)

// 4N lanes as N vectors of four (SSE2, or SIMD128): N chains of steps,
// each one's latency hidden behind the others' (a rotation takes three
// operations, so a step's chain is long).
template <int N>
struct Vectors {
  __m128i v[N];
};
#define M4MESH_VECTORS_OF(name, op)                                  \
  template <int N>                                                   \
  inline Vectors<N> name(const Vectors<N>& x, const Vectors<N>& y) { \
    Vectors<N> out;                                                  \
    for (int i = 0; i < N; ++i) out.v[i] = op(x.v[i], y.v[i]);       \
    return out;                                                      \
  }
M4MESH_VECTORS_OF(vectors_xor, _mm_xor_si128)
M4MESH_VECTORS_OF(vectors_and, _mm_and_si128)
M4MESH_VECTORS_OF(vectors_or, _mm_or_si128)
M4MESH_VECTORS_OF(vectors_add, _mm_add_epi32)
#undef M4MESH_VECTORS_OF
template <int N>
Vectors<N> vectors_set1(int value) {
  Vectors<N> out;
  for (int i = 0; i < N; ++i) out.v[i] = _mm_set1_epi32(value);
  return out;
}
template <int kShift, int N>
Vectors<N> vectors_sll(const Vectors<N>& x) {
  Vectors<N> out;
  for (int i = 0; i < N; ++i) out.v[i] = _mm_slli_epi32(x.v[i], kShift);
  return out;
}
template <int kShift, int N>
Vectors<N> vectors_srl(const Vectors<N>& x) {
  Vectors<N> out;
  for (int i = 0; i < N; ++i) out.v[i] = _mm_srli_epi32(x.v[i], kShift);
  return out;
}

#define M4MESH_V_XOR vectors_xor
#define M4MESH_V_AND vectors_and
#define M4MESH_V_OR vectors_or
#define M4MESH_V_ADD vectors_add
#define M4MESH_V_SET1(x) vectors_set1<N>(x)
#define M4MESH_V_SLL(x, s) vectors_sll<s>(x)
#define M4MESH_V_SRL(x, s) vectors_srl<s>(x)

// One 64-byte block of each of 4N lanes' messages: lanes 4q … 4q + 3 in vector q.
template <int N>
void blocks_of_vectors(LaneState<4 * N>& state, const uint8_t* const lane[4 * N]) {
  Vectors<N> w[16];
  for (int k = 0; k < 4; ++k)
    for (int q = 0; q < N; ++q) {
      __m128i words[4];
      transpose4(lane + 4 * q, k, words);
      for (int j = 0; j < 4; ++j) w[4 * k + j].v[q] = words[j];
    }
  Vectors<N> in[4];
  for (int i = 0; i < 4; ++i)
    for (int q = 0; q < N; ++q) in[i].v[q] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(state[i] + 4 * q));
  Vectors<N> a = in[0], b = in[1], c = in[2], d = in[3];
  M4MESH_MD5_ROUNDS(M4MESH_STEP, M4MESH_F, M4MESH_G, M4MESH_H, M4MESH_I)
  const Vectors<N> rounds[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i)
    for (int q = 0; q < N; ++q) _mm_storeu_si128(reinterpret_cast<__m128i*>(state[i] + 4 * q), _mm_add_epi32(in[i].v[q], rounds[i].v[q]));
}

#ifdef M4MESH_MD5_AVX2

#undef M4MESH_V_XOR
#undef M4MESH_V_AND
#undef M4MESH_V_OR
#undef M4MESH_V_ADD
#undef M4MESH_V_SET1
#undef M4MESH_V_SLL
#undef M4MESH_V_SRL
#define M4MESH_V_XOR _mm256_xor_si256
#define M4MESH_V_AND _mm256_and_si256
#define M4MESH_V_OR _mm256_or_si256
#define M4MESH_V_ADD _mm256_add_epi32
#define M4MESH_V_SET1 _mm256_set1_epi32
#define M4MESH_V_SLL _mm256_slli_epi32
#define M4MESH_V_SRL _mm256_srli_epi32

// One 64-byte block of each of eight lanes' messages (AVX2): lanes 0–3 transposed in the low halves, 4–7 in the high.
__attribute__((target("avx2"))) void blocks8(LaneState<8>& state, const uint8_t* const lane[8]) {
  __m256i w[16];
  for (int k = 0; k < 4; ++k) {
    __m128i low[4], high[4];
    transpose4(lane, k, low);
    transpose4(lane + 4, k, high);
    for (int j = 0; j < 4; ++j) w[4 * k + j] = _mm256_inserti128_si256(_mm256_castsi128_si256(low[j]), high[j], 1);
  }
  __m256i in[4];
  for (int i = 0; i < 4; ++i) in[i] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(state[i]));
  __m256i a = in[0], b = in[1], c = in[2], d = in[3];
  M4MESH_MD5_ROUNDS(M4MESH_STEP, M4MESH_F, M4MESH_G, M4MESH_H, M4MESH_I)
  const __m256i rounds[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) _mm256_storeu_si256(reinterpret_cast<__m256i*>(state[i]), _mm256_add_epi32(in[i], rounds[i]));
}

// One 64-byte block of each of sixteen lanes' messages (AVX-512): lanes 4q … 4q + 3 transposed in the
// q-th 128 bits. Its rotation and three-input logic take one instruction each, so a step's chain is shorter.
__attribute__((target("avx512f"))) void blocks16(LaneState<16>& state, const uint8_t* const lane[16]) {
  __m512i w[16];
  for (int k = 0; k < 4; ++k) {
    __m128i quarter[4][4];
    for (int q = 0; q < 4; ++q) transpose4(lane + 4 * q, k, quarter[q]);
    for (int j = 0; j < 4; ++j) {
      __m512i word = _mm512_castsi128_si512(quarter[0][j]);
      word = _mm512_inserti32x4(word, quarter[1][j], 1);
      word = _mm512_inserti32x4(word, quarter[2][j], 2);
      w[4 * k + j] = _mm512_inserti32x4(word, quarter[3][j], 3);
    }
  }
  __m512i in[4];
  for (int i = 0; i < 4; ++i) in[i] = _mm512_loadu_si512(state[i]);
  __m512i a = in[0], b = in[1], c = in[2], d = in[3];
  // RFC 1321's F, G, H and I as truth tables of (b, c, d).
#define M4MESH_F16(b, c, d) _mm512_ternarylogic_epi32(b, c, d, 0xca)
#define M4MESH_G16(b, c, d) _mm512_ternarylogic_epi32(b, c, d, 0xe4)
#define M4MESH_H16(b, c, d) _mm512_ternarylogic_epi32(b, c, d, 0x96)
#define M4MESH_I16(b, c, d) _mm512_ternarylogic_epi32(b, c, d, 0x39)
// The rotation all-lanes masked: GCC 12's unmasked _mm512_rol_epi32 trips -Wuninitialized in its own header.
#define M4MESH_STEP16(f, a, b, c, d, word, s, constant)                                      \
  do {                                                                                        \
    const __m512i wk = _mm512_add_epi32(word, _mm512_set1_epi32(static_cast<int>(constant))); \
    const __m512i sum = _mm512_add_epi32(_mm512_add_epi32(a, f(b, c, d)), wk);               \
    a = _mm512_add_epi32(b, _mm512_maskz_rol_epi32(0xffff, sum, s));                          \
  } while (false)
  M4MESH_MD5_ROUNDS(M4MESH_STEP16, M4MESH_F16, M4MESH_G16, M4MESH_H16, M4MESH_I16)
  const __m512i rounds[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) _mm512_storeu_si512(state[i], _mm512_add_epi32(in[i], rounds[i]));
}

#endif

// N messages of `length` bytes, a block of each at a time.
template <size_t N>
void lanes(const uint8_t* const messages[N], size_t length, std::array<uint8_t, 16>* out,
           void (*blocks)(LaneState<N>&, const uint8_t* const[N])) {
  LaneState<N> state;
  for (size_t l = 0; l < N; ++l) {
    state[0][l] = 0x67452301;
    state[1][l] = 0xefcdab89;
    state[2][l] = 0x98badcfe;
    state[3][l] = 0x10325476;
  }
  const size_t whole = length / 64;
  const uint8_t* at[N];
  for (size_t b = 0; b < whole; ++b) {
    for (size_t l = 0; l < N; ++l) at[l] = messages[l] + 64 * b;
    blocks(state, at);
  }
  // The tail, 0x80, zeros and the length in bits: one or two blocks, the same shape in every lane.
  const size_t tail = length % 64, padded = tail < 56 ? 64 : 128;
  uint8_t last[N][128];
  const uint64_t bits = uint64_t{length} * 8;
  for (size_t l = 0; l < N; ++l) {
    std::memset(last[l], 0, padded);
    std::memcpy(last[l], messages[l] + 64 * whole, tail);
    last[l][tail] = 0x80;
    for (int i = 0; i < 8; ++i) last[l][padded - 8 + static_cast<size_t>(i)] = static_cast<uint8_t>(bits >> (8 * i));
  }
  for (size_t b = 0; b < padded; b += 64) {
    for (size_t l = 0; l < N; ++l) at[l] = last[l] + b;
    blocks(state, at);
  }
  for (size_t l = 0; l < N; ++l)
    for (int i = 0; i < 4; ++i)
      for (int byte = 0; byte < 4; ++byte) out[l][static_cast<size_t>(4 * i + byte)] = static_cast<uint8_t>(state[i][l] >> (8 * byte));
}

#endif

}  // namespace

void md5_of_equal_lengths(std::span<const uint8_t* const> messages, size_t length, std::span<std::array<uint8_t, 16>> out,
                          [[maybe_unused]] int widest_bits) {
  size_t k = 0;
#ifdef M4MESH_MD5_LANES
#ifdef M4MESH_MD5_AVX2
  if (widest_bits >= 512 && has_avx512f())
    for (; k + 16 <= messages.size(); k += 16) lanes<16>(messages.data() + k, length, out.data() + k, blocks16);
  if (widest_bits >= 256 && has_avx2())
    for (; k + 8 <= messages.size(); k += 8) lanes<8>(messages.data() + k, length, out.data() + k, blocks8);
#endif
  if (widest_bits >= 128) {
    for (; k + 16 <= messages.size(); k += 16) lanes<16>(messages.data() + k, length, out.data() + k, blocks_of_vectors<4>);
    for (; k + 8 <= messages.size(); k += 8) lanes<8>(messages.data() + k, length, out.data() + k, blocks_of_vectors<2>);
    for (; k + 4 <= messages.size(); k += 4) lanes<4>(messages.data() + k, length, out.data() + k, blocks_of_vectors<1>);
  }
#endif
  one_by_one(messages.subspan(k), length, out.subspan(k));
}

}  // namespace m4mesh
