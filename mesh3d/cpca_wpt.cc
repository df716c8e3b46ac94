#include "mesh3d/cpca_wpt.h"

#include <type_traits>

#if defined(__SSE2__) || defined(__wasm_simd128__)
#include <emmintrin.h>
#define M4MESH_CPCA_SIMD 1
#endif

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

CpcaAnimation::CpcaAnimation(const CpcaHeader& header, std::span<const IntPoint3> mean_shape, uint32_t frames)
    : mean_shape_(mean_shape.begin(), mean_shape.end()), fraction_bits_(header.fraction_bits) {
  const double scale = 1.0 / static_cast<double>(uint64_t{1} << header.fraction_bits);
  for (int axis = 0; axis < 3; ++axis) {
    origin_[axis] = header.origin_value(axis);
    unit_[axis] = static_cast<double>(header.step_value(axis)) * scale;
  }
  reset(frames);
}

void CpcaAnimation::reset(uint32_t frames) {
  frames_ = frames;
  fixed_.resize(size_t{frames} * mean_shape_.size() * 3);
  for (uint32_t f = 0; f < frames; ++f)
    for (size_t v = 0; v < mean_shape_.size(); ++v) {
      const size_t element = (size_t{f} * mean_shape_.size() + v) * 3;
      for (int axis = 0; axis < 3; ++axis)
        fixed_[element + static_cast<size_t>(axis)] = static_cast<uint64_t>(int64_t{mean_shape_[v][axis]}) << fraction_bits_;
    }
}

Float3 CpcaAnimation::position(uint32_t f, NodeIndex v) const {
  const size_t element = (size_t{f} * mean_shape_.size() + v) * 3;
  Float3 p;
  for (int axis = 0; axis < 3; ++axis)
    p[axis] = static_cast<float>(origin_[axis] + static_cast<double>(static_cast<int64_t>(fixed_[element + static_cast<size_t>(axis)])) * unit_[axis]);
  return p;
}

void CpcaAnimation::frame(uint32_t f, std::span<Float3> positions) const {
  NodeIndex v = 0;
#ifdef M4MESH_CPCA_SIMD
  // Two vertices (six values, three pairs of axes) at a time, the same IEEE steps as position(): a
  // value below 2^51 in magnitude becomes its double exactly by the 1.5 · 2^52 bias; pairs beyond it
  // take position().
  const __m128d origin[3] = {_mm_set_pd(origin_[1], origin_[0]), _mm_set_pd(origin_[0], origin_[2]), _mm_set_pd(origin_[2], origin_[1])};
  const __m128d unit[3] = {_mm_set_pd(unit_[1], unit_[0]), _mm_set_pd(unit_[0], unit_[2]), _mm_set_pd(unit_[2], unit_[1])};
  const __m128i bias = _mm_set1_epi64x(0x4338000000000000), half_range = _mm_set1_epi64x(int64_t{1} << 51);
  const __m128d biased = _mm_castsi128_pd(bias);
  const uint64_t* values = fixed_.data() + size_t{f} * mean_shape_.size() * 3;
  float* out = positions.data()->data();
  for (; v + 2 <= positions.size(); v += 2) {
    __m128i x[3];
    __m128i outside = _mm_setzero_si128();
    for (int k = 0; k < 3; ++k) {
      x[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(values + 3 * size_t{v} + 2 * static_cast<size_t>(k)));
      outside = _mm_or_si128(outside, _mm_srli_epi64(_mm_add_epi64(x[k], half_range), 52));
    }
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(outside, _mm_setzero_si128())) != 0xFFFF) {
      positions[v] = position(f, v), positions[v + 1] = position(f, v + 1);
      continue;
    }
    __m128 low = _mm_setzero_ps(), high = _mm_setzero_ps();
    for (int k = 0; k < 3; ++k) {
      const __m128d exact = _mm_sub_pd(_mm_castsi128_pd(_mm_add_epi64(x[k], bias)), biased);
      const __m128 pair = _mm_cvtpd_ps(_mm_add_pd(origin[k], _mm_mul_pd(exact, unit[k])));
      if (k == 0) low = pair;
      if (k == 1) low = _mm_movelh_ps(low, pair);
      if (k == 2) high = pair;
    }
    _mm_storeu_ps(out + 3 * size_t{v}, low);
    _mm_storel_pi(reinterpret_cast<__m64*>(out + 3 * size_t{v} + 4), high);
  }
#endif
  for (; v < positions.size(); ++v) positions[v] = position(f, v);
}

void CpcaAnimation::mean_frame(std::span<Float3> positions) const {
  for (size_t v = 0; v < positions.size(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      positions[v][axis] = static_cast<float>(
          origin_[axis] + static_cast<double>(static_cast<int64_t>(static_cast<uint64_t>(int64_t{mean_shape_[v][axis]}) << fraction_bits_)) * unit_[axis]);
}

namespace {

// value × 2^−t, rounded (halves up) when t > 0; |value| ≤ 2^38, t ≥ −16.
int64_t scaled(int64_t value, int t) { return t > 0 ? (value + (int64_t{1} << (t - 1))) >> t : value * (int64_t{1} << -t); }

}  // namespace

void CpcaAnimation::translate(std::span<const NodeIndex> members, std::span<const int32_t> translation, uint32_t shift, bool undo) {
  const int t = static_cast<int>(shift) - static_cast<int>(kCpcaShiftBias);
  for (uint32_t f = 0; f < frames_; ++f) {
    uint64_t term[3];
    for (size_t axis = 0; axis < 3; ++axis) {
      term[axis] = static_cast<uint64_t>(scaled(translation[3 * size_t{f} + axis], t));
      if (undo) term[axis] = 0 - term[axis];
    }
    for (NodeIndex m : members) {
      const size_t at = size_t{f} * mean_shape_.size() + m;
      for (size_t axis = 0; axis < 3; ++axis) fixed_[3 * at + axis] += term[axis];
    }
  }
}

void CpcaAnimation::refine(std::span<const NodeIndex> members, std::span<const int32_t> basis, std::span<const int32_t> coefficients,
                           uint32_t shift, bool trajectory, bool undo) {
  const int t = static_cast<int>(shift) - static_cast<int>(kCpcaShiftBias);
  // One pass per kind and direction, its indexing known at compile time (the decoder's hot loop).
  const auto pass = [&](auto kind, auto subtract) {
    constexpr bool kTrajectory = decltype(kind)::value, kSubtract = decltype(subtract)::value;
    // Member i's basis value on an axis is basis[i · per_member + axis · per_axis].
    constexpr size_t per_member = kTrajectory ? 1 : 3, per_axis = kTrajectory ? 0 : 1;
    for (uint32_t f = 0; f < frames_; ++f) {
      int64_t c[3];
      for (size_t axis = 0; axis < 3; ++axis) c[axis] = kTrajectory ? coefficients[3 * size_t{f} + axis] : coefficients[f];
      for (size_t i = 0; i < members.size(); ++i) {
        const size_t at = size_t{f} * mean_shape_.size() + members[i];
        for (size_t axis = 0; axis < 3; ++axis) {
          const uint64_t term = static_cast<uint64_t>(scaled(basis[i * per_member + axis * per_axis] * c[axis], t));
          if constexpr (kSubtract)
            fixed_[3 * at + axis] -= term;
          else
            fixed_[3 * at + axis] += term;
        }
      }
    }
  };
  if (trajectory && undo)
    pass(std::true_type{}, std::true_type{});
  else if (trajectory)
    pass(std::true_type{}, std::false_type{});
  else if (undo)
    pass(std::false_type{}, std::true_type{});
  else
    pass(std::false_type{}, std::false_type{});
}

}  // namespace m4mesh
