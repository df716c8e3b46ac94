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
#endif

#include "common/cpu.h"
#include "mesh3d/position_order.h"

namespace m4mesh {

std::vector<std::vector<NodeIndex>> cpca_members(std::span<const uint32_t> cluster_of, uint32_t cluster_count) {
  std::vector<std::vector<NodeIndex>> members(cluster_count);
  for (NodeIndex v = 0; v < cluster_of.size(); ++v) members[cluster_of[v]].push_back(v);
  return members;
}

CpcaMeshPrediction::CpcaMeshPrediction(std::span<const Triangle> faces, std::span<const uint32_t> coding_order,
                                       std::span<const uint32_t> cluster_of, uint32_t cluster_count, std::span<const IntPoint3> mean_shape)
    : predictor_(faces, static_cast<uint32_t>(cluster_of.size())),
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
  const __m128i bias = _mm_set1_epi64x(0x4338000000000000), half_range = _mm_set1_epi64x(int64_t{1} << 51);
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
  static constexpr uint64_t kBias = 0x4338000000000000, kTop = uint64_t{1} << 63;
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

}  // namespace

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
    : slots_(header, mean_shape, members), frames_(frames), terms_(members.size()), run_(3 * slots_.largest_cluster()) {}

void CpcaSegment::translate(uint32_t cluster, std::vector<int32_t> translation, uint32_t shift) {
  terms_[cluster].push_back({kCpcaStart, shift, nullptr, std::move(translation)});
}

void CpcaSegment::refine(uint32_t cluster, std::shared_ptr<const std::vector<int32_t>> basis, std::vector<int32_t> coefficients, uint32_t shift,
                         bool trajectory) {
  terms_[cluster].push_back({trajectory ? kCpcaTrajectory : kCpcaComponent, shift, std::move(basis), std::move(coefficients)});
}

void CpcaSegment::reset(uint32_t frames) {
  frames_ = frames;
  for (std::vector<Term>& cluster : terms_) cluster.clear();
}

void CpcaSegment::frame(uint32_t f, std::span<Float3> positions) const {
  const std::vector<uint64_t>& mean = slots_.mean();
  for (uint32_t c = 0; c < terms_.size(); ++c) {
    const size_t first = slots_.first_value(c), count = slots_.value_count(c);
    uint64_t* run = run_.data();
    std::copy_n(mean.begin() + static_cast<ptrdiff_t>(first), count, run);
    for (const Term& term : terms_[c]) {
      const bool trajectory = term.kind == kCpcaTrajectory;
      if (term.kind == kCpcaStart)
        add_translation(run, count, translation_terms(term.values, f, exponent_of(term.shift), false));
      else
        cpca_add_terms(std::span(run, count), *term.basis, coefficients_of(term.values, f, trajectory), term.shift, trajectory);
    }
    slots_.convert(run, first / 3, count / 3, positions);
  }
}

void CpcaSegment::mean_frame(std::span<Float3> positions) const { slots_.convert(slots_.mean().data(), 0, slots_.vertex_count(), positions); }

}  // namespace m4mesh
