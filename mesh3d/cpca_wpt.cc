#include "mesh3d/cpca_wpt.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

#if !defined(M4MESH_NO_SIMD) && (defined(__SSE2__) || defined(__wasm_simd128__))
#include <emmintrin.h>
#define M4MESH_CPCA_SIMD 1
#if defined(__x86_64__) && !defined(__EMSCRIPTEN__)
#include <immintrin.h>
#define M4MESH_CPCA_AVX2 1  // chosen at run time, where the processor has it
#endif
#ifdef __wasm_simd128__
#include <wasm_simd128.h>
#define M4MESH_CPCA_WASM 1  // SIMD128's own integer products for the block sums
#endif
#endif

#include "common/bit_cast.h"
#include "common/cpu.h"
#include "mesh3d/position_order.h"

namespace m4mesh {

#ifdef M4MESH_CPCA_SIMD
namespace {
// 1.5 · 2^52's binary64 bits: added to an integer below 2^51 in magnitude they are the bits of that integer plus
// the bias, exactly (the vector loops' conversions of integers and products to and from binary64).
constexpr int64_t kExactBias = 0x4338000000000000, kExactRange = int64_t{1} << 51;
}  // namespace
#endif

std::vector<std::vector<NodeIndex>> cpca_members(std::span<const uint32_t> cluster_of, uint32_t cluster_count) {
  std::vector<std::vector<NodeIndex>> members(cluster_count);
  for (NodeIndex v = 0; v < cluster_of.size(); ++v) members[cluster_of[v]].push_back(v);
  return members;
}

CpcaMeshPrediction::CpcaMeshPrediction(std::span<const Triangle> faces, std::span<const uint32_t> coding_order,
                                       std::span<const uint32_t> cluster_of, uint32_t cluster_count, std::span<const IntPoint3> mean_shape)
    : CpcaMeshPrediction(MeshPredictor(faces, static_cast<uint32_t>(cluster_of.size())), coding_order, cluster_of, cluster_count,
                         mean_shape) {}

CpcaMeshPrediction::CpcaMeshPrediction(MeshPredictor predictor, std::span<const uint32_t> coding_order, std::span<const uint32_t> cluster_of,
                                       uint32_t cluster_count, std::span<const IntPoint3> mean_shape)
    : predictor_(std::move(predictor)),
      mean_shape_(mean_shape.begin(), mean_shape.end()),
      rank_(cluster_of.size()),
      slot_(cluster_of.size()),
      cluster_of_(cluster_of.begin(), cluster_of.end()),
      in_order_(cluster_count) {
  std::vector<uint32_t> members(cluster_count, 0);
  for (NodeIndex v = 0; v < cluster_of.size(); ++v) slot_[v] = members[cluster_of[v]]++;
  for (const uint32_t v : coding_order) in_order_[cluster_of[v]].push_back(v);
  PositionOrder by_support(predictor_, static_cast<uint32_t>(cluster_of.size()));
  for (std::vector<uint32_t>& order : in_order_) {
    order = by_support.of(order);
    for (uint32_t i = 0; i < order.size(); ++i) rank_[order[i]] = i;
  }
}

void CpcaMeshPrediction::keep_fits() {
  for (uint32_t cluster = 0; cluster < in_order_.size(); ++cluster) keep_fits(cluster);
}

void CpcaMeshPrediction::keep_fits(uint32_t cluster) {
  if (fits_.empty()) fits_.resize(cluster_of_.size()), kept_.assign(in_order_.size(), 0);
  if (kept_[cluster]) return;
  kept_[cluster] = 1;
  std::vector<uint32_t> points;
  for (const uint32_t v : in_order_[cluster]) {
    const uint32_t rank = rank_[v];
    KeptFit& fit = fits_[v];
    fit.channel = affine_fit_support(predictor_, v, [&](uint32_t u) { return rank_[u] < rank && cluster_of_[u] == cluster; }, points);
    fit.first = static_cast<uint32_t>(fit_points_.size());
    fit.count = static_cast<uint32_t>(points.size());
    fit_points_.insert(fit_points_.end(), points.begin(), points.end());
    fit_q_.resize(fit_points_.size());
    if (fit.channel >= 0) fit.shape = affine_fit_shape(mean_shape_, v, points, std::span(fit_q_.data() + fit.first, fit.count));
  }
}

CpcaSlots::CpcaSlots(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members)
    : slot_of_vertex_(mean_shape.size()) {
  for (const std::vector<NodeIndex>& cluster : members) {
    first_slot_.push_back(vertex_of_slot_.size());
    largest_ = std::max(largest_, cluster.size());
    for (const NodeIndex v : cluster) {
      slot_of_vertex_[v] = static_cast<NodeIndex>(vertex_of_slot_.size());
      vertex_of_slot_.push_back(v);
      for (size_t axis = 0; axis < 3; ++axis) mean_.push_back(static_cast<uint64_t>(int64_t{mean_shape[v][axis]}) << header.fraction_bits);
    }
  }
  first_slot_.push_back(vertex_of_slot_.size());
  const double scale = 1.0 / static_cast<double>(uint64_t{1} << header.fraction_bits);
  for (int axis = 0; axis < 3; ++axis) {
    origin_[axis] = header.origin_value(axis);
    unit_[axis] = static_cast<double>(header.step_value(axis)) * scale;
  }
}

Float3 CpcaSlots::position(const uint64_t* values) const {
  Float3 p;
  for (int axis = 0; axis < 3; ++axis)
    p[axis] = static_cast<float>(origin_[axis] + static_cast<double>(static_cast<int64_t>(values[axis])) * unit_[axis]);
  return p;
}

void CpcaSlots::convert(const uint64_t* values, size_t first_slot, size_t slots, std::span<Float3> positions) const {
  const NodeIndex* vertex = vertex_of_slot_.data() + first_slot;
  size_t s = 0;
#ifdef M4MESH_CPCA_SIMD
  // Two slots (six values, three pairs of axes) at a time, the same IEEE steps as position(): a
  // value below 2^51 in magnitude becomes its double exactly by the 1.5 · 2^52 bias; pairs beyond it
  // take position().
  const __m128d origin[3] = {_mm_set_pd(origin_[1], origin_[0]), _mm_set_pd(origin_[0], origin_[2]), _mm_set_pd(origin_[2], origin_[1])};
  const __m128d unit[3] = {_mm_set_pd(unit_[1], unit_[0]), _mm_set_pd(unit_[0], unit_[2]), _mm_set_pd(unit_[2], unit_[1])};
  const __m128i bias = _mm_set1_epi64x(kExactBias), half_range = _mm_set1_epi64x(kExactRange);
  const __m128d biased = _mm_castsi128_pd(bias);
  for (; s + 2 <= slots; s += 2) {
    Float3& first = positions[vertex[s]];
    Float3& second = positions[vertex[s + 1]];
    __m128i x[3];
    __m128i outside = _mm_setzero_si128();
    for (size_t k = 0; k < 3; ++k) {
      x[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(values + 3 * s + 2 * k));
      outside = _mm_or_si128(outside, _mm_srli_epi64(_mm_add_epi64(x[k], half_range), 52));
    }
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(outside, _mm_setzero_si128())) != 0xFFFF) {
      first = position(values + 3 * s), second = position(values + 3 * s + 3);
      continue;
    }
    __m128 low = _mm_setzero_ps(), high = _mm_setzero_ps();
    for (size_t k = 0; k < 3; ++k) {
      const __m128d exact = _mm_sub_pd(_mm_castsi128_pd(_mm_add_epi64(x[k], bias)), biased);
      const __m128 pair = _mm_cvtpd_ps(_mm_add_pd(origin[k], _mm_mul_pd(exact, unit[k])));
      if (k == 0) low = pair;
      if (k == 1) low = _mm_movelh_ps(low, pair);
      if (k == 2) high = pair;
    }
    alignas(16) float both[8];
    _mm_store_ps(both, low);
    _mm_storel_pi(reinterpret_cast<__m64*>(both + 4), high);
    std::memcpy(first.data(), both, sizeof first);
    std::memcpy(second.data(), both + 3, sizeof second);
  }
#endif
  for (; s < slots; ++s) positions[vertex[s]] = position(values + 3 * s);
}

#ifdef M4MESH_CPCA_AVX2
namespace {

// convert_blocked's blocks in AVX2's four lanes, an axis a vector, up to the first block with a value beyond 2^51
// in magnitude; returns how many blocks it took. No FMA: the product and the sum stay two roundings.
__attribute__((target("avx2"))) size_t convert_blocks_avx2(const uint64_t* values, const NodeIndex* vertex, size_t blocks,
                                                           const std::array<double, 3>& origin, const std::array<double, 3>& unit,
                                                           Float3* positions) {
  const __m256i bias = _mm256_set1_epi64x(kExactBias), half_range = _mm256_set1_epi64x(kExactRange);
  const __m256d biased = _mm256_castsi256_pd(bias);
  const __m256d origins[3] = {_mm256_set1_pd(origin[0]), _mm256_set1_pd(origin[1]), _mm256_set1_pd(origin[2])};
  const __m256d units[3] = {_mm256_set1_pd(unit[0]), _mm256_set1_pd(unit[1]), _mm256_set1_pd(unit[2])};
  for (size_t b = 0; b < blocks; ++b) {
    const uint64_t* block = values + 3 * kCpcaBlock * b;
    __m256i x[3];
    __m256i outside = _mm256_setzero_si256();
    for (size_t a = 0; a < 3; ++a) {
      x[a] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(block + kCpcaBlock * a));
      outside = _mm256_or_si256(outside, _mm256_srli_epi64(_mm256_add_epi64(x[a], half_range), 52));
    }
    if (!_mm256_testz_si256(outside, outside)) return b;
    __m128 axis[3];
    for (size_t a = 0; a < 3; ++a) {
      const __m256d exact = _mm256_sub_pd(_mm256_castsi256_pd(_mm256_add_epi64(x[a], bias)), biased);
      axis[a] = _mm256_cvtpd_ps(_mm256_add_pd(origins[a], _mm256_mul_pd(exact, units[a])));
    }
    // Each member's x and y as a pair, its z alone.
    const __m128 xy[2] = {_mm_unpacklo_ps(axis[0], axis[1]), _mm_unpackhi_ps(axis[0], axis[1])};
    const NodeIndex* members = vertex + kCpcaBlock * b;
    float* at[kCpcaBlock];
    for (size_t m = 0; m < kCpcaBlock; ++m) at[m] = positions[members[m]].data();
    _mm_storel_pi(reinterpret_cast<__m64*>(at[0]), xy[0]);
    _mm_storeh_pi(reinterpret_cast<__m64*>(at[1]), xy[0]);
    _mm_storel_pi(reinterpret_cast<__m64*>(at[2]), xy[1]);
    _mm_storeh_pi(reinterpret_cast<__m64*>(at[3]), xy[1]);
    _MM_EXTRACT_FLOAT(at[0][2], axis[2], 0);
    _MM_EXTRACT_FLOAT(at[1][2], axis[2], 1);
    _MM_EXTRACT_FLOAT(at[2][2], axis[2], 2);
    _MM_EXTRACT_FLOAT(at[3][2], axis[2], 3);
  }
  return blocks;
}

}  // namespace
#endif

void CpcaSlots::convert_blocked(const uint64_t* values, size_t first_slot, size_t slots, std::span<Float3> positions) const {
  const NodeIndex* vertex = vertex_of_slot_.data() + first_slot;
  size_t s = 0;
#ifdef M4MESH_CPCA_SIMD
  // A block a time, two members of an axis a vector, convert()'s IEEE steps; a block with a value beyond 2^51 in
  // magnitude takes position(). Where the processor has AVX2, its loop takes the blocks up to such a one.
  const __m128i bias = _mm_set1_epi64x(kExactBias), half_range = _mm_set1_epi64x(kExactRange);
  const __m128d biased = _mm_castsi128_pd(bias);
  for (; s + kCpcaBlock <= slots; s += kCpcaBlock) {
#ifdef M4MESH_CPCA_AVX2
    if (has_avx2()) {
      s += kCpcaBlock * convert_blocks_avx2(values + 3 * s, vertex + s, (slots - s) / kCpcaBlock, origin_, unit_, positions.data());
      if (s + kCpcaBlock > slots) break;
    }
#endif
    const uint64_t* block = values + 3 * s;
    __m128i x[6];
    __m128i outside = _mm_setzero_si128();
    for (size_t k = 0; k < 6; ++k) {
      x[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(block + 2 * k));
      outside = _mm_or_si128(outside, _mm_srli_epi64(_mm_add_epi64(x[k], half_range), 52));
    }
    alignas(16) float axes[3][kCpcaBlock];
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(outside, _mm_setzero_si128())) != 0xFFFF) {
      for (size_t m = 0; m < kCpcaBlock; ++m) {
        const uint64_t member[3] = {block[m], block[kCpcaBlock + m], block[2 * kCpcaBlock + m]};
        positions[vertex[s + m]] = position(member);
      }
      continue;
    }
    for (size_t a = 0; a < 3; ++a) {
      const __m128d origin = _mm_set1_pd(origin_[a]), unit = _mm_set1_pd(unit_[a]);
      const __m128 low = _mm_cvtpd_ps(_mm_add_pd(origin, _mm_mul_pd(_mm_sub_pd(_mm_castsi128_pd(_mm_add_epi64(x[2 * a], bias)), biased), unit)));
      const __m128 high = _mm_cvtpd_ps(_mm_add_pd(origin, _mm_mul_pd(_mm_sub_pd(_mm_castsi128_pd(_mm_add_epi64(x[2 * a + 1], bias)), biased), unit)));
      _mm_store_ps(axes[a], _mm_movelh_ps(low, high));
    }
    for (size_t m = 0; m < kCpcaBlock; ++m) positions[vertex[s + m]] = {axes[0][m], axes[1][m], axes[2][m]};
  }
#else
  for (; s + kCpcaBlock <= slots; s += kCpcaBlock)
    for (size_t m = 0; m < kCpcaBlock; ++m) {
      const uint64_t member[3] = {values[3 * s + m], values[3 * s + kCpcaBlock + m], values[3 * s + 2 * kCpcaBlock + m]};
      positions[vertex[s + m]] = position(member);
    }
#endif
  convert(values + 3 * s, first_slot + s, slots - s, positions);
}

namespace {

// value × 2^−t, rounded (halves up) when t > 0; |value| ≤ 2^38, t ≥ −16.
int64_t scaled(int64_t value, int t) { return t > 0 ? (value + (int64_t{1} << (t - 1))) >> t : value * (int64_t{1} << -t); }

// A start's terms on one frame's run: run[3i + a] += term[a].
void add_translation(uint64_t* run, size_t n, const std::array<uint64_t, 3>& term) {
  for (size_t j = 0; j < n; j += 3)
    for (size_t axis = 0; axis < 3; ++axis) run[j + axis] += term[axis];
}

// A start's terms on frame f (`undo`: their negation).
std::array<uint64_t, 3> translation_terms(std::span<const int32_t> translation, uint32_t f, int u, bool undo) {
  std::array<uint64_t, 3> term;
  for (size_t axis = 0; axis < 3; ++axis) {
    term[axis] = static_cast<uint64_t>(scaled(translation[3 * size_t{f} + axis], u));
    if (undo) term[axis] = 0 - term[axis];
  }
  return term;
}

int exponent_of(uint32_t shift) { return static_cast<int>(shift) - static_cast<int>(kCpcaShiftBias); }

// Coefficient lanes of frame f for the three axes: one value, or three with a trajectory component.
std::array<int64_t, 3> coefficients_of(std::span<const int32_t> coefficients, uint32_t f, bool trajectory) {
  if (trajectory) return {coefficients[3 * size_t{f}], coefficients[3 * size_t{f} + 1], coefficients[3 * size_t{f} + 2]};
  return {coefficients[f], coefficients[f], coefficients[f]};
}

#ifdef M4MESH_CPCA_SIMD
// The vector loops' scaled(p, u), p a product exact in binary64 (|p| ≤ 2^38): p + 1.5 · 2^52 (the bias) makes
// its integer the low bits; `before` takes the bias out and adds the rounding half and 2^63, so that the
// rounding shift is a logical one, and `after` takes 2^(63 − u) out after it; u ≤ 0 shifts left.
struct TermScaling {
  static constexpr uint64_t kBias = kExactBias, kTop = uint64_t{1} << 63;
  explicit TermScaling(int u)
      : before(u > 0 ? (uint64_t{1} << (u - 1)) + kTop - kBias : 0 - kBias),
        after(u > 0 ? kTop >> u : 0),
        right(u > 0 ? u : 0),
        left(u < 0 ? -u : 0) {}
  uint64_t before, after;
  int right, left;
};
#endif

#ifdef M4MESH_CPCA_AVX2
// The SSE2 loop's arithmetic in AVX2's four lanes, twelve values at a time; returns how many it took. No FMA:
// the product and the bias stay two roundings of exact values.
template <bool kTrajectory, bool kSubtract, bool kRounded>
__attribute__((target("avx2"))) size_t add_terms_avx2(uint64_t* run, const int32_t* basis, size_t n, const std::array<int64_t, 3>& coefficient,
                                                      const TermScaling& scaling) {
  const double c0 = static_cast<double>(coefficient[0]), c1 = static_cast<double>(coefficient[1]), c2 = static_cast<double>(coefficient[2]);
  const __m256d lanes[3] = {_mm256_set_pd(c0, c2, c1, c0), _mm256_set_pd(c1, c0, c2, c1), _mm256_set_pd(c2, c1, c0, c2)};
  const __m256d biased = _mm256_castsi256_pd(_mm256_set1_epi64x(static_cast<int64_t>(TermScaling::kBias)));
  const __m256i before = _mm256_set1_epi64x(static_cast<int64_t>(scaling.before)), after = _mm256_set1_epi64x(static_cast<int64_t>(scaling.after));
  const __m128i right = _mm_cvtsi32_si128(scaling.right), left = _mm_cvtsi32_si128(scaling.left);
  size_t j = 0;
  const int32_t* next = basis;
  for (; j + 12 <= n; j += 12) {
    __m256d b[3];
    if constexpr (kTrajectory) {
      const __m256d four = _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(next)));
      b[0] = _mm256_permute4x64_pd(four, 0x40);  // b0 b0 b0 b1
      b[1] = _mm256_permute4x64_pd(four, 0xa5);  // b1 b1 b2 b2
      b[2] = _mm256_permute4x64_pd(four, 0xfe);  // b2 b3 b3 b3
      next += 4;
    } else {
      for (size_t k = 0; k < 3; ++k) b[k] = _mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(next + 4 * k)));
      next += 12;
    }
    for (size_t k = 0; k < 3; ++k) {
      const __m256i p = _mm256_add_epi64(_mm256_castpd_si256(_mm256_add_pd(_mm256_mul_pd(b[k], lanes[k]), biased)), before);
      const __m256i term = kRounded ? _mm256_sub_epi64(_mm256_srl_epi64(p, right), after) : _mm256_sll_epi64(p, left);
      __m256i* at = reinterpret_cast<__m256i*>(run + j + 4 * k);
      _mm256_storeu_si256(at, kSubtract ? _mm256_sub_epi64(_mm256_loadu_si256(at), term) : _mm256_add_epi64(_mm256_loadu_si256(at), term));
    }
  }
  return j;
}
#endif

// run[j] ±= scaled(b(j) × coefficient[j mod 3], u) for j < n, a multiple
// of 3: one unit's terms on one frame's run of a cluster. b(j) is
// basis[j], or with kTrajectory basis[j / 3].
template <bool kTrajectory, bool kSubtract>
void add_terms(uint64_t* run, const int32_t* basis, size_t n, const std::array<int64_t, 3>& coefficient, int u) {
  size_t j = 0;
#ifdef M4MESH_CPCA_SIMD
  // Six values (three pairs) at a time, after the AVX2 loop's twelve where the processor has it.
  const TermScaling scaling(u);
  const __m128d pairs[3] = {_mm_set_pd(static_cast<double>(coefficient[1]), static_cast<double>(coefficient[0])),
                            _mm_set_pd(static_cast<double>(coefficient[0]), static_cast<double>(coefficient[2])),
                            _mm_set_pd(static_cast<double>(coefficient[2]), static_cast<double>(coefficient[1]))};
  const __m128d biased = _mm_castsi128_pd(_mm_set1_epi64x(static_cast<int64_t>(TermScaling::kBias)));
  const __m128i before = _mm_set1_epi64x(static_cast<int64_t>(scaling.before)), after = _mm_set1_epi64x(static_cast<int64_t>(scaling.after));
  const __m128i right = _mm_cvtsi32_si128(scaling.right), left = _mm_cvtsi32_si128(scaling.left);
  // The exponent's sign chooses the loops: a rounding shift right, or a shift left.
  const auto six_at_a_time = [&](auto rounded) {
#ifdef M4MESH_CPCA_AVX2
    if (has_avx2()) j = add_terms_avx2<kTrajectory, kSubtract, decltype(rounded)::value>(run, basis, n, coefficient, scaling);
#endif
    const int32_t* next = basis + (kTrajectory ? j / 3 : j);
    for (; j + 6 <= n; j += 6) {
      __m128d b[3];
      if constexpr (kTrajectory) {
        const __m128d two = _mm_cvtepi32_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(next)));
        b[0] = _mm_unpacklo_pd(two, two), b[1] = two, b[2] = _mm_unpackhi_pd(two, two);
        next += 2;
      } else {
        for (size_t k = 0; k < 3; ++k) b[k] = _mm_cvtepi32_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(next + 2 * k)));
        next += 6;
      }
      for (size_t k = 0; k < 3; ++k) {
        const __m128i p = _mm_add_epi64(_mm_castpd_si128(_mm_add_pd(_mm_mul_pd(b[k], pairs[k]), biased)), before);
        const __m128i term = decltype(rounded)::value ? _mm_sub_epi64(_mm_srl_epi64(p, right), after) : _mm_sll_epi64(p, left);
        __m128i* at = reinterpret_cast<__m128i*>(run + j + 2 * k);
        _mm_storeu_si128(at, kSubtract ? _mm_sub_epi64(_mm_loadu_si128(at), term) : _mm_add_epi64(_mm_loadu_si128(at), term));
      }
    }
  };
  if (u > 0)
    six_at_a_time(std::true_type{});
  else
    six_at_a_time(std::false_type{});
#endif
  for (; j < n; ++j) {
    const uint64_t term = static_cast<uint64_t>(scaled(int64_t{basis[kTrajectory ? j / 3 : j]} * coefficient[j % 3], u));
    run[j] = kSubtract ? run[j] - term : run[j] + term;
  }
}

#ifdef M4MESH_CPCA_AVX2
// The terms on a block's three axes (acc[a]: its members' axis a), the products exact in int64 lanes.
template <bool kTrajectory, bool kRounded, class Lanes>
__attribute__((target("avx2"))) inline void add_block_avx2(__m256i (&acc)[3], const std::vector<Lanes>& terms, size_t block) {
  for (const Lanes& t : terms) {
    const int32_t* b = t.blocked + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
    const __m128i right = _mm_cvtsi64_si128(static_cast<int64_t>(t.right)), left = _mm_cvtsi64_si128(static_cast<int64_t>(t.left));
    const __m256i members = _mm256_cvtepi32_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(b)));
    for (size_t a = 0; a < 3; ++a) {
      const __m256i basis = kTrajectory ? members : _mm256_cvtepi32_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(b + kCpcaBlock * a)));
      const __m256i p = _mm256_mul_epi32(basis, _mm256_set1_epi64x(static_cast<int64_t>(t.coefficient[a])));
      const __m256i term = kRounded ? _mm256_srl_epi64(_mm256_add_epi64(p, _mm256_set1_epi64x(static_cast<int64_t>(t.before))), right)
                                    : _mm256_sll_epi64(p, left);
      acc[a] = _mm256_add_epi64(acc[a], term);
    }
  }
}

// From member `first` (a whole block's).
template <class Lanes>
__attribute__((target("avx2"))) size_t sum_blocks_avx2(const uint64_t* mean, size_t first, size_t members, uint64_t* run,
                                                       const std::array<uint64_t, 3>& start, const std::vector<Lanes> (&lanes)[2][3]) {
  size_t i = first;
  for (; i + kCpcaBlock <= members; i += kCpcaBlock) {
    __m256i acc[3];
    for (size_t a = 0; a < 3; ++a)
      acc[a] = _mm256_add_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(mean + 3 * i + kCpcaBlock * a)),
                                _mm256_set1_epi64x(static_cast<int64_t>(start[a])));
    add_block_avx2<false, false>(acc, lanes[0][0], i / kCpcaBlock);
    add_block_avx2<false, true>(acc, lanes[0][1], i / kCpcaBlock);
    add_block_avx2<true, false>(acc, lanes[1][0], i / kCpcaBlock);
    add_block_avx2<true, true>(acc, lanes[1][1], i / kCpcaBlock);
    add_block_avx2<false, false>(acc, lanes[0][2], i / kCpcaBlock);
    add_block_avx2<true, false>(acc, lanes[1][2], i / kCpcaBlock);
    for (size_t a = 0; a < 3; ++a) _mm256_storeu_si256(reinterpret_cast<__m256i*>(run + 3 * i + kCpcaBlock * a), acc[a]);
  }
  return i;
}

// Two blocks' basis values as they meet values 8k … 8k + 7 of the two (basis[k]): a trajectory component's
// members meet their axes' coefficients as the two blocks' values are laid out (x, y | z, x | y, z of the
// first block, then the second).
template <bool kTrajectory>
__attribute__((target("avx2"))) inline void load_pair_avx2(const int32_t* blocked, size_t block, __m256i (&basis)[3]) {
  const int32_t* b = blocked + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
  if constexpr (kTrajectory) {
    const __m256i members = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b));
    basis[0] = _mm256_permute2x128_si256(members, members, 0x00);
    basis[1] = members;
    basis[2] = _mm256_permute2x128_si256(members, members, 0x11);
  } else {
    for (size_t k = 0; k < 3; ++k) basis[k] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b + 2 * kCpcaBlock * k));
  }
}

// The terms on two blocks' values in int32 lanes (acc[k]: values 8k … 8k + 7 of the two), where narrow_on
// found that they and their sums fit.
template <bool kTrajectory, bool kRounded, class Lanes>
__attribute__((target("avx2"))) inline void add_pair_narrow_avx2(__m256i (&acc)[3], const std::vector<Lanes>& terms, size_t block) {
  for (const Lanes& t : terms) {
    __m256i basis[3];
    load_pair_avx2<kTrajectory>(t.blocked, block, basis);
    const __m128i right = _mm_cvtsi64_si128(static_cast<int64_t>(t.right)), left = _mm_cvtsi64_si128(static_cast<int64_t>(t.left));
    const __m256i half = _mm256_set1_epi32(t.half);
    for (size_t k = 0; k < 3; ++k) {
      const __m256i p = _mm256_mullo_epi32(basis[k], _mm256_load_si256(reinterpret_cast<const __m256i*>(t.narrow.data() + 2 * kCpcaBlock * k)));
      acc[k] = _mm256_add_epi32(acc[k], kRounded ? _mm256_sra_epi32(_mm256_add_epi32(p, half), right) : _mm256_sll_epi32(p, left));
    }
  }
}

// The same with term pairs (CpcaTermSum::TermPair): a multiply-add of int16 halves a pair.
template <bool kTrajectory, class TermPair>
__attribute__((target("avx2"))) inline void add_term_pairs_avx2(__m256i (&acc)[3], const std::vector<TermPair>& pairs, size_t block) {
  for (const TermPair& p : pairs) {
    __m256i basis[3];
    load_pair_avx2<kTrajectory>(p.basis.data(), block, basis);
    for (size_t k = 0; k < 3; ++k)
      acc[k] = _mm256_add_epi32(acc[k], _mm256_madd_epi16(basis[k], _mm256_load_si256(reinterpret_cast<const __m256i*>(p.narrow.data() + 2 * kCpcaBlock * k))));
  }
}

// Two whole blocks at a time, the terms summed in int32 lanes and then added to the mean in int64 ones;
// returns how many members it took.
template <class Lanes, class TermPair>
__attribute__((target("avx2"))) size_t sum_pairs_narrow_avx2(const uint64_t* mean, size_t members, uint64_t* run, const std::array<uint64_t, 3>& start,
                                                             const std::vector<Lanes> (&lanes)[2][3], const std::vector<TermPair> (&term_pairs)[2],
                                                             bool paired) {
  size_t i = 0;
  for (; i + 2 * kCpcaBlock <= members; i += 2 * kCpcaBlock) {
    __m256i acc[3] = {_mm256_setzero_si256(), _mm256_setzero_si256(), _mm256_setzero_si256()};
    add_pair_narrow_avx2<false, false>(acc, lanes[0][0], i / kCpcaBlock);
    add_pair_narrow_avx2<false, true>(acc, lanes[0][1], i / kCpcaBlock);
    add_pair_narrow_avx2<true, false>(acc, lanes[1][0], i / kCpcaBlock);
    add_pair_narrow_avx2<true, true>(acc, lanes[1][1], i / kCpcaBlock);
    if (paired) {
      add_term_pairs_avx2<false>(acc, term_pairs[0], i / kCpcaBlock);
      add_term_pairs_avx2<true>(acc, term_pairs[1], i / kCpcaBlock);
    } else {
      add_pair_narrow_avx2<false, false>(acc, lanes[0][2], i / kCpcaBlock);
      add_pair_narrow_avx2<true, false>(acc, lanes[1][2], i / kCpcaBlock);
    }
    for (size_t k = 0; k < 3; ++k) {
      const __m256i sums[2] = {_mm256_cvtepi32_epi64(_mm256_castsi256_si128(acc[k])), _mm256_cvtepi32_epi64(_mm256_extracti128_si256(acc[k], 1))};
      for (size_t h = 0; h < 2; ++h) {
        // Four values of one axis: the blocks' x, y, z, x, y, z in turn.
        const size_t at = 3 * i + kCpcaBlock * (2 * k + h);
        const __m256i base = _mm256_add_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(mean + at)),
                                              _mm256_set1_epi64x(static_cast<int64_t>(start[(2 * k + h) % 3])));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(run + at), _mm256_add_epi64(base, sums[h]));
      }
    }
  }
  return i;
}
#endif

#ifdef M4MESH_CPCA_SIMD
// The terms on a block's three axes, two members a vector (acc[2a + h]: members 2h, 2h + 1, axis a), the
// products exact in binary64 lanes (TermScaling).
template <bool kTrajectory, bool kRounded, class Lanes>
inline void add_block_sse2(__m128i (&acc)[6], const std::vector<Lanes>& terms, size_t block) {
  const __m128d biased = _mm_castsi128_pd(_mm_set1_epi64x(static_cast<int64_t>(TermScaling::kBias)));
  for (const Lanes& t : terms) {
    const int32_t* b = t.blocked + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
    const __m128i before = _mm_set1_epi64x(static_cast<int64_t>(t.before));
    const __m128i right = _mm_cvtsi64_si128(static_cast<int64_t>(t.right)), left = _mm_cvtsi64_si128(static_cast<int64_t>(t.left));
    for (size_t a = 0; a < 3; ++a) {
      const __m128d w = _mm_castsi128_pd(_mm_set1_epi64x(static_cast<int64_t>(t.coefficient[a])));
      for (size_t h = 0; h < 2; ++h) {
        const int32_t* pair = b + (kTrajectory ? 0 : kCpcaBlock * a) + 2 * h;
        const __m128d basis = _mm_cvtepi32_pd(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(pair)));
        const __m128i p = _mm_add_epi64(_mm_castpd_si128(_mm_add_pd(_mm_mul_pd(basis, w), biased)), before);
        const __m128i term = kRounded ? _mm_srl_epi64(p, right) : _mm_sll_epi64(p, left);
        acc[2 * a + h] = _mm_add_epi64(acc[2 * a + h], term);
      }
    }
  }
}

template <class Lanes>
size_t sum_blocks_sse2(const uint64_t* mean, size_t members, uint64_t* run, const std::array<uint64_t, 3>& start,
                       const std::vector<Lanes> (&lanes)[2][3]) {
  size_t i = 0;
  for (; i + kCpcaBlock <= members; i += kCpcaBlock) {
    __m128i acc[6];
    for (size_t k = 0; k < 6; ++k)
      acc[k] = _mm_add_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(mean + 3 * i + 2 * k)), _mm_set1_epi64x(static_cast<int64_t>(start[k / 2])));
    add_block_sse2<false, false>(acc, lanes[0][0], i / kCpcaBlock);
    add_block_sse2<false, true>(acc, lanes[0][1], i / kCpcaBlock);
    add_block_sse2<true, false>(acc, lanes[1][0], i / kCpcaBlock);
    add_block_sse2<true, true>(acc, lanes[1][1], i / kCpcaBlock);
    add_block_sse2<false, false>(acc, lanes[0][2], i / kCpcaBlock);
    add_block_sse2<true, false>(acc, lanes[1][2], i / kCpcaBlock);
    for (size_t k = 0; k < 6; ++k) _mm_storeu_si128(reinterpret_cast<__m128i*>(run + 3 * i + 2 * k), acc[k]);
  }
  return i;
}
#endif

#ifdef M4MESH_CPCA_WASM
// The terms on a block's three axes, two members a vector (acc[2a + h]: members 2h, 2h + 1, axis a), the
// products exact in int64 lanes (i64x2.extmul) as AVX2's.
template <bool kTrajectory, bool kRounded, class Lanes>
inline void add_block_wasm(v128_t (&acc)[6], const std::vector<Lanes>& terms, size_t block) {
  for (const Lanes& t : terms) {
    const int32_t* b = t.blocked + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
    const v128_t before = wasm_i64x2_splat(static_cast<int64_t>(t.before));
    const v128_t members = wasm_v128_load(b);
    for (size_t a = 0; a < 3; ++a) {
      const v128_t basis = kTrajectory ? members : wasm_v128_load(b + kCpcaBlock * a);
      const v128_t w = wasm_v128_load(t.coefficient[a].data());
      const v128_t p[2] = {wasm_i64x2_extmul_low_i32x4(basis, w), wasm_i64x2_extmul_high_i32x4(basis, w)};
      for (size_t h = 0; h < 2; ++h) {
        const v128_t term = kRounded ? wasm_u64x2_shr(wasm_i64x2_add(p[h], before), static_cast<uint32_t>(t.right))
                                     : wasm_i64x2_shl(p[h], static_cast<uint32_t>(t.left));
        acc[2 * a + h] = wasm_i64x2_add(acc[2 * a + h], term);
      }
    }
  }
}

// The terms on a block's three axes in int32 lanes (acc[a]: its members' axis a), where narrow_on found that
// they and their sums fit.
template <bool kTrajectory, bool kRounded, class Lanes>
inline void add_block_narrow_wasm(v128_t (&acc)[3], const std::vector<Lanes>& terms, size_t block) {
  for (const Lanes& t : terms) {
    const int32_t* b = t.blocked + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
    const v128_t members = wasm_v128_load(b);
    const v128_t half = wasm_i32x4_splat(t.half);
    for (size_t a = 0; a < 3; ++a) {
      const v128_t basis = kTrajectory ? members : wasm_v128_load(b + kCpcaBlock * a);
      const v128_t p = wasm_i32x4_mul(basis, wasm_v128_load(t.narrow.data() + kCpcaBlock * a));
      acc[a] = wasm_i32x4_add(acc[a], kRounded ? wasm_i32x4_shr(wasm_i32x4_add(p, half), static_cast<uint32_t>(t.right))
                                               : wasm_i32x4_shl(p, static_cast<uint32_t>(t.left)));
    }
  }
}

// The same with term pairs (CpcaTermSum::TermPair): a multiply-add of int16 halves a pair.
template <bool kTrajectory, class TermPair>
inline void add_term_pairs_wasm(v128_t (&acc)[3], const std::vector<TermPair>& pairs, size_t block) {
  for (const TermPair& p : pairs) {
    const int32_t* b = p.basis.data() + (kTrajectory ? 1 : 3) * kCpcaBlock * block;
    const v128_t members = wasm_v128_load(b);
    for (size_t a = 0; a < 3; ++a) {
      const v128_t basis = kTrajectory ? members : wasm_v128_load(b + kCpcaBlock * a);
      acc[a] = wasm_i32x4_add(acc[a], wasm_i32x4_dot_i16x8(basis, wasm_v128_load(p.narrow.data() + kCpcaBlock * a)));
    }
  }
}

// A whole block at a time, the terms summed in int32 lanes and then added to the mean in int64 ones; returns
// how many members it took.
template <class Lanes, class TermPair>
size_t sum_blocks_narrow_wasm(const uint64_t* mean, size_t members, uint64_t* run, const std::array<uint64_t, 3>& start,
                              const std::vector<Lanes> (&lanes)[2][3], const std::vector<TermPair> (&term_pairs)[2], bool paired) {
  size_t i = 0;
  for (; i + kCpcaBlock <= members; i += kCpcaBlock) {
    v128_t acc[3] = {wasm_i32x4_splat(0), wasm_i32x4_splat(0), wasm_i32x4_splat(0)};
    add_block_narrow_wasm<false, false>(acc, lanes[0][0], i / kCpcaBlock);
    add_block_narrow_wasm<false, true>(acc, lanes[0][1], i / kCpcaBlock);
    add_block_narrow_wasm<true, false>(acc, lanes[1][0], i / kCpcaBlock);
    add_block_narrow_wasm<true, true>(acc, lanes[1][1], i / kCpcaBlock);
    if (paired) {
      add_term_pairs_wasm<false>(acc, term_pairs[0], i / kCpcaBlock);
      add_term_pairs_wasm<true>(acc, term_pairs[1], i / kCpcaBlock);
    } else {
      add_block_narrow_wasm<false, false>(acc, lanes[0][2], i / kCpcaBlock);
      add_block_narrow_wasm<true, false>(acc, lanes[1][2], i / kCpcaBlock);
    }
    for (size_t a = 0; a < 3; ++a) {
      const v128_t sums[2] = {wasm_i64x2_extend_low_i32x4(acc[a]), wasm_i64x2_extend_high_i32x4(acc[a])};
      for (size_t h = 0; h < 2; ++h) {
        const size_t at = 3 * i + kCpcaBlock * a + 2 * h;
        wasm_v128_store(run + at, wasm_i64x2_add(wasm_i64x2_add(wasm_v128_load(mean + at), wasm_i64x2_splat(static_cast<int64_t>(start[a]))), sums[h]));
      }
    }
  }
  return i;
}

template <class Lanes>
size_t sum_blocks_wasm(const uint64_t* mean, size_t members, uint64_t* run, const std::array<uint64_t, 3>& start,
                       const std::vector<Lanes> (&lanes)[2][3]) {
  size_t i = 0;
  for (; i + kCpcaBlock <= members; i += kCpcaBlock) {
    v128_t acc[6];
    for (size_t k = 0; k < 6; ++k) acc[k] = wasm_i64x2_add(wasm_v128_load(mean + 3 * i + 2 * k), wasm_i64x2_splat(static_cast<int64_t>(start[k / 2])));
    add_block_wasm<false, false>(acc, lanes[0][0], i / kCpcaBlock);
    add_block_wasm<false, true>(acc, lanes[0][1], i / kCpcaBlock);
    add_block_wasm<true, false>(acc, lanes[1][0], i / kCpcaBlock);
    add_block_wasm<true, true>(acc, lanes[1][1], i / kCpcaBlock);
    add_block_wasm<false, false>(acc, lanes[0][2], i / kCpcaBlock);
    add_block_wasm<true, false>(acc, lanes[1][2], i / kCpcaBlock);
    for (size_t k = 0; k < 6; ++k) wasm_v128_store(run + 3 * i + 2 * k, acc[k]);
  }
  return i;
}
#endif

}  // namespace

CpcaTermSum::CpcaTermSum() {
#if defined(M4MESH_CPCA_WASM)
  integer_ = true;
#elif defined(M4MESH_CPCA_AVX2)
  integer_ = has_avx2();
#endif
}

void CpcaTermSum::clear() {
  starts_.clear(), after_ = 0;
  for (auto& by_kind : lanes_)
    for (std::vector<Lanes>& lanes : by_kind) lanes.clear();
  for (std::vector<TermPair>& pairs : term_pairs_) pairs.clear();
  unpaired_ = {};
}

void CpcaTermSum::translate(const int32_t* translation, uint32_t shift) { starts_.emplace_back(translation, exponent_of(shift)); }

void CpcaTermSum::add(const int32_t* basis, const int32_t* blocked, size_t count, const int32_t* coefficients, uint32_t shift, bool trajectory,
                      int32_t largest_basis) {
  const int u = exponent_of(shift);
  Lanes& term = lanes_[trajectory][u > 0 ? kRounded : kUnrounded].emplace_back(Lanes{basis, blocked, coefficients, u, largest_basis, {}, 0, 0, 0, {}, 0});
  // A rounding half beyond int32 never meets the narrow loops (narrow_on).
  term.half = u > 0 && u < 32 ? int32_t{1} << (u - 1) : 0;
#ifdef M4MESH_CPCA_SIMD
  const TermScaling scaling(u);
  // AVX2 and SIMD128 multiply in int64 lanes (no bias to take out), SSE2 in binary64 ones.
  term.before = integer_ ? scaling.before + TermScaling::kBias : scaling.before;
  term.right = static_cast<uint64_t>(scaling.right), term.left = static_cast<uint64_t>(scaling.left);
  after_ += scaling.after;
#else
  (void)term;
#endif
  // The second of two terms that pair: both move to kPaired, their basis values interleaved. Only the
  // narrow loops (integer_) read pairs.
  if (!integer_ || u > 0 || largest_basis >= 1 << 15) return;
  std::vector<Lanes>& unrounded = lanes_[trajectory][kUnrounded];
  if (unpaired_[trajectory] == 0) {
    unpaired_[trajectory] = unrounded.size();
    return;
  }
  const size_t first = unpaired_[trajectory] - 1;
  unpaired_[trajectory] = 0;
  std::vector<Lanes>& paired = lanes_[trajectory][kPaired];
  paired.push_back(unrounded[first]);
  paired.push_back(unrounded.back());
  unrounded.pop_back();
  unrounded.erase(unrounded.begin() + static_cast<ptrdiff_t>(first));
  TermPair& pair = term_pairs_[trajectory].emplace_back();
  pair.basis.resize(count);
  const int32_t *low = paired[paired.size() - 2].blocked, *high = paired.back().blocked;
  for (size_t j = 0; j < count; ++j) pair.basis[j] = static_cast<int32_t>(static_cast<uint16_t>(low[j]) | uint32_t{static_cast<uint16_t>(high[j])} << 16);
}

size_t CpcaTermSum::sum_blocks([[maybe_unused]] const uint64_t* mean, [[maybe_unused]] size_t members, [[maybe_unused]] uint64_t* run,
                               [[maybe_unused]] bool narrow, [[maybe_unused]] bool paired) const {
#ifdef M4MESH_CPCA_SIMD
  // The rounded terms' 2^(63 − u) taken out once, with the translations.
  std::array<uint64_t, 3> start;
  for (size_t axis = 0; axis < 3; ++axis) start[axis] = offset_[axis] - after_;
#if defined(M4MESH_CPCA_WASM)
  if (narrow) return sum_blocks_narrow_wasm(mean, members, run, offset_, lanes_, term_pairs_, paired);
  return sum_blocks_wasm(mean, members, run, start, lanes_);
#else
#ifdef M4MESH_CPCA_AVX2
  if (integer_)
    return sum_blocks_avx2(mean, narrow ? sum_pairs_narrow_avx2(mean, members, run, offset_, lanes_, term_pairs_, paired) : 0, members, run, start,
                           lanes_);
#endif
  return sum_blocks_sse2(mean, members, run, start, lanes_);
#endif
#else
  return 0;
#endif
}

bool CpcaTermSum::narrow_on(uint32_t n) {
  constexpr uint64_t kNarrow = uint64_t{1} << 31;
  uint64_t sum = 0;  // of the terms' greatest magnitudes
  for (size_t trajectory = 0; trajectory < 2; ++trajectory)
    for (std::vector<Lanes>& by_kind : lanes_[trajectory])
      for (Lanes& t : by_kind) {
        uint64_t coefficient = 0;  // the greatest |coefficient| of the axes
        for (size_t axis = 0; axis < 3; ++axis) {
          const int32_t w = t.coefficients[trajectory ? 3 * size_t{n} + axis : n];
          for (size_t k = axis; k < 6; k += 3) std::fill_n(t.narrow.begin() + static_cast<ptrdiff_t>(kCpcaBlock * k), kCpcaBlock, w);
          coefficient = std::max<uint64_t>(coefficient, static_cast<uint64_t>(w < 0 ? -int64_t{w} : int64_t{w}));
        }
        // |b × w| ≤ 2^38, and with a rounding half h below 2^31: then |term| ≤ (|b × w| + h) / 2^u.
        const uint64_t product = coefficient * static_cast<uint64_t>(t.largest_basis);
        const uint64_t reach = t.u > 0 ? product + (uint64_t{1} << (t.u - 1)) : product;
        if (reach >= kNarrow) return false;
        sum += t.u > 0 ? reach >> t.u : reach << -t.u;
        if (sum >= kNarrow) return false;
      }
  return true;
}

bool CpcaTermSum::term_pairs_on(uint32_t n) {
  for (size_t trajectory = 0; trajectory < 2; ++trajectory)
    for (size_t p = 0; p < term_pairs_[trajectory].size(); ++p) {
      const Lanes* terms = &lanes_[trajectory][kPaired][2 * p];
      for (size_t axis = 0; axis < 3; ++axis) {
        uint32_t halves = 0;
        for (size_t k = 0; k < 2; ++k) {
          const int64_t w = int64_t{terms[k].coefficients[trajectory ? 3 * size_t{n} + axis : n]} * (int64_t{1} << -terms[k].u);
          if (w < -(1 << 15) || w >= 1 << 15) return false;
          halves |= uint32_t{static_cast<uint16_t>(w)} << (16 * k);
        }
        for (size_t g = axis; g < 6; g += 3)
          std::fill_n(term_pairs_[trajectory][p].narrow.begin() + static_cast<ptrdiff_t>(kCpcaBlock * g), kCpcaBlock, static_cast<int32_t>(halves));
      }
    }
  return true;
}

void CpcaTermSum::sum(uint32_t n, const uint64_t* mean, size_t members, uint64_t* run) {
  offset_ = {};
  for (const auto& [translation, u] : starts_)
    for (size_t axis = 0; axis < 3; ++axis) offset_[axis] += static_cast<uint64_t>(scaled(translation[3 * size_t{n} + axis], u));
#ifdef M4MESH_CPCA_SIMD
  for (size_t trajectory = 0; trajectory < 2; ++trajectory)
    for (std::vector<Lanes>& by_kind : lanes_[trajectory])
      for (Lanes& t : by_kind)
        for (size_t axis = 0; axis < 3; ++axis) {
          const int32_t w = t.coefficients[trajectory ? 3 * size_t{n} + axis : n];
#ifdef M4MESH_CPCA_WASM
          t.coefficient[axis] = {w, w, w, w};
#else
          t.coefficient[axis] = integer_ ? static_cast<uint64_t>(int64_t{w}) : bit_cast<uint64_t>(static_cast<double>(w));
#endif
        }
#endif
  const size_t whole = members / kCpcaBlock * kCpcaBlock;
#if defined(M4MESH_CPCA_AVX2) || defined(M4MESH_CPCA_WASM)
  const bool narrow = integer_ && narrow_on(n);
#else
  const bool narrow = false;
#endif
  const bool paired = narrow && term_pairs_on(n);
  for (size_t j = 3 * sum_blocks(mean, members, run, narrow, paired); j < 3 * members; ++j) {
    // In a whole block, value j is member j mod 4 of it, axis (j mod 12) / 4; after them, member j / 3, axis j mod 3.
    const bool in_block = j < 3 * whole;
    const size_t member = in_block ? j / (3 * kCpcaBlock) * kCpcaBlock + j % kCpcaBlock : j / 3;
    const size_t axis = in_block ? j % (3 * kCpcaBlock) / kCpcaBlock : j % 3;
    uint64_t value = mean[j] + offset_[axis];
    for (size_t kind = 0; kind < 3; ++kind) {
      for (const Lanes& t : lanes_[0][kind]) value += static_cast<uint64_t>(scaled(int64_t{t.basis[3 * member + axis]} * t.coefficients[n], t.u));
      for (const Lanes& t : lanes_[1][kind])
        value += static_cast<uint64_t>(scaled(int64_t{t.basis[member]} * t.coefficients[3 * size_t{n} + axis], t.u));
    }
    run[j] = value;
  }
}

void cpca_add_terms(std::span<uint64_t> run, std::span<const int32_t> basis, const std::array<int64_t, 3>& lanes, uint32_t shift,
                    bool trajectory, bool subtract) {
  const int u = exponent_of(shift);
  if (trajectory)
    subtract ? add_terms<true, true>(run.data(), basis.data(), run.size(), lanes, u) : add_terms<true, false>(run.data(), basis.data(), run.size(), lanes, u);
  else
    subtract ? add_terms<false, true>(run.data(), basis.data(), run.size(), lanes, u) : add_terms<false, false>(run.data(), basis.data(), run.size(), lanes, u);
}

CpcaAnimation::CpcaAnimation(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members,
                             uint32_t frames)
    : slots_(header, mean_shape, members), frames_(frames) {
  const std::vector<uint64_t>& mean = slots_.mean();
  fixed_.reserve(size_t{frames} * mean.size());
  for (uint32_t f = 0; f < frames; ++f) fixed_.insert(fixed_.end(), mean.begin(), mean.end());
}

Float3 CpcaAnimation::position(uint32_t f, NodeIndex v) const {
  return slots_.position(fixed_.data() + (size_t{f} * slots_.vertex_count() + slots_.slot_of(v)) * 3);
}

void CpcaAnimation::frame(uint32_t f, std::span<Float3> positions) const {
  slots_.convert(fixed_.data() + size_t{f} * slots_.vertex_count() * 3, 0, slots_.vertex_count(), positions);
}

void CpcaAnimation::translate(uint32_t cluster, std::span<const int32_t> translation, uint32_t shift, bool undo) {
  for (uint32_t f = 0; f < frames_; ++f)
    add_translation(fixed_.data() + size_t{f} * slots_.vertex_count() * 3 + slots_.first_value(cluster), slots_.value_count(cluster),
                    translation_terms(translation, f, exponent_of(shift), undo));
}

void CpcaAnimation::refine(uint32_t cluster, std::span<const int32_t> basis, std::span<const int32_t> coefficients, uint32_t shift,
                           bool trajectory, bool undo) {
  for (uint32_t f = 0; f < frames_; ++f)
    cpca_add_terms(std::span(fixed_).subspan(size_t{f} * slots_.vertex_count() * 3 + slots_.first_value(cluster), slots_.value_count(cluster)),
                   basis, coefficients_of(coefficients, f, trajectory), shift, trajectory, undo);
}

CpcaSegment::CpcaSegment(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, std::span<const std::vector<NodeIndex>> members,
                         uint32_t frames)
    : slots_(header, mean_shape, members),
      blocked_mean_(slots_.mean().size()),
      frames_(frames),
      terms_(members.size()),
      run_(3 * slots_.largest_cluster()),
      sums_(members.size()) {
  for (uint32_t c = 0; c < members.size(); ++c)
    cpca_blocked(slots_.mean().data() + slots_.first_value(c), members[c].size(), blocked_mean_.data() + slots_.first_value(c));
}

void CpcaSegment::translate(uint32_t cluster, std::vector<int32_t> translation, uint32_t shift) {
  const Term& term = terms_[cluster].emplace_back(Term{nullptr, std::move(translation), {}});
  sums_[cluster].translate(term.values.data(), shift);
}

void CpcaSegment::refine(uint32_t cluster, std::shared_ptr<const std::vector<int32_t>> basis, std::vector<int32_t> coefficients, uint32_t shift,
                         bool trajectory) {
  std::vector<int32_t> blocked;
  if (!trajectory) {
    blocked.resize(basis->size());
    cpca_blocked(basis->data(), basis->size() / 3, blocked.data());
  }
  const Term& term = terms_[cluster].emplace_back(Term{std::move(basis), std::move(coefficients), std::move(blocked)});
  int32_t largest = 0;
  for (const int32_t b : *term.basis) largest = std::max(largest, b < 0 ? -b : b);
  sums_[cluster].add(term.basis->data(), trajectory ? term.basis->data() : term.blocked.data(), term.basis->size(), term.values.data(), shift,
                     trajectory, largest);
}

void CpcaSegment::reset(uint32_t frames) {
  frames_ = frames;
  for (std::vector<Term>& cluster : terms_) cluster.clear();
  for (CpcaTermSum& sum : sums_) sum.clear();
}

void CpcaSegment::frame(uint32_t f, std::span<Float3> positions) const { frames(f, std::span(&positions, 1)); }

// Cluster by cluster, each of its frames in turn: a cluster's basis and its terms' coefficients for these frames
// are read from the cache after the first frame, not from memory once a frame.
void CpcaSegment::frames(uint32_t first_frame, std::span<const std::span<Float3>> positions) const {
  for (uint32_t c = 0; c < terms_.size(); ++c) {
    const size_t first = slots_.first_value(c), members = slots_.value_count(c) / 3;
    for (size_t k = 0; k < positions.size(); ++k) {
      sums_[c].sum(first_frame + static_cast<uint32_t>(k), blocked_mean_.data() + first, members, run_.data());
      slots_.convert_blocked(run_.data(), first / 3, members, positions[k]);
    }
  }
}

void CpcaSegment::mean_frame(std::span<Float3> positions) const { slots_.convert(slots_.mean().data(), 0, slots_.vertex_count(), positions); }

}  // namespace m4mesh
