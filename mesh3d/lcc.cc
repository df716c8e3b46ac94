#include "mesh3d/lcc.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#if !defined(M4MESH_NO_SIMD) && (defined(__SSE2__) || defined(__wasm_simd128__))
#include <emmintrin.h>
#define M4MESH_LCC_PAIRS 1
#endif

namespace m4mesh {

namespace {

Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 cross(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// a / |a|, or nothing (false) for a zero vector.
bool normalized(const Vec3& a, Vec3& unit) {
  const double length = std::sqrt(dot(a, a));
  if (!(length > 0)) return false;
  unit = {a.x / length, a.y / length, a.z / length};
  return true;
}

// sin x and cos x for 0 ≤ x ≤ π/4: Taylor series to x^19 and x^18 in
// Horner form (truncation below 10^−18).
void sin_cos(double x, double& s, double& c) {
  const double x2 = x * x;
  s = 1;
  c = 1;
  for (int n = 9; n >= 1; --n) {
    s = 1 - x2 / static_cast<double>((2 * n) * (2 * n + 1)) * s;
    c = 1 - x2 / static_cast<double>((2 * n - 1) * (2 * n)) * c;
  }
  s = x * s;
}

// atan2(y, x) within 10^−9 and without a branch, for the encoder's
// measurement of every vertex's θ (a θ that close to a rounding boundary
// may take the neighbouring index, a choice the decoder does not see):
// the octant's ratio, folded into [−tan π/8, tan π/8] around π/4, then
// atan's Taylor series to u^19.
double angle_of(double y, double x) {
  constexpr double kPi = std::numbers::pi, kTanPiOver8 = 0.41421356237309503;
  const double ax = std::fabs(x), ay = std::fabs(y);
  const double big = std::max(ax, ay), small = std::min(ax, ay);
  const bool fold = small > kTanPiOver8 * big;
  const double u = (fold ? small - big : small) / (fold ? small + big : big > 0 ? big : 1);
  const double u2 = u * u;
  double series = 1.0 / 19;
  for (const double odd : {1.0 / 17, 1.0 / 15, 1.0 / 13, 1.0 / 11, 1.0 / 9, 1.0 / 7, 1.0 / 5, 1.0 / 3, 1.0}) series = odd - u2 * series;
  double r = (fold ? kPi / 4 : 0) + u * series;
  r = ay > ax ? kPi / 2 - r : r;
  r = std::signbit(x) ? kPi - r : r;
  return std::copysign(r, y);
}

}  // namespace

LccOrder lcc_order(std::span<const Triangle> faces, size_t vertex_count) {
  LccOrder order;
  const TriangleNeighbours neighbours = triangle_neighbours(faces, vertex_count);
  std::vector<uint8_t> coded(vertex_count, 0), reached(faces.size(), 0);
  std::vector<uint32_t> stack;
  auto code_directly = [&](NodeIndex v) {
    if (coded[v]) return;
    coded[v] = 1;
    order.direct.push_back(v);
  };
  for (uint32_t root = 0; root < faces.size(); ++root) {
    if (reached[root]) continue;
    reached[root] = 1;
    for (NodeIndex v : faces[root].v) code_directly(v);
    stack.assign(1, root);
    while (!stack.empty()) {
      const uint32_t f = stack.back();
      stack.pop_back();
      const Triangle& t = faces[f];
      // The neighbours across v0 → v1, v1 → v2, v2 → v0 are taken in this
      // order and pushed in the reverse, so that the first is walked first.
      uint32_t next[3];
      for (int e = 0; e < 3; ++e) {
        const NodeIndex a = t.v[(e + 2) % 3], b = t.v[e], c = t.v[(e + 1) % 3];
        const uint32_t g = neighbours[f][(e + 2) % 3];
        next[e] = kNoTriangle;
        if (g == kNoTriangle || reached[g]) continue;
        reached[g] = 1;
        next[e] = g;
        const NodeIndex d = faces[g].third(b, c);
        if (!coded[d]) {
          coded[d] = 1;
          order.steps.push_back({d, a, b, c});
        }
      }
      for (int e = 2; e >= 0; --e)
        if (next[e] != kNoTriangle) stack.push_back(next[e]);
    }
  }
  for (NodeIndex v = 0; v < vertex_count; ++v) code_directly(v);
  return order;
}

LccCodedFrame LccFrameOrder::next() {
  if (!pending_.empty()) {
    const auto [l, r] = pending_.back();
    pending_.pop_back();
    const uint32_t m = l + (r - l) / 2;
    if (r - m >= 2) pending_.emplace_back(m, r);
    if (m - l >= 2) pending_.emplace_back(l, m);
    return {m, l, r};
  }
  const uint64_t f = anchor_;
  if (previous_ != kLccAnchor && f - previous_ >= 2) pending_.emplace_back(static_cast<uint32_t>(previous_), static_cast<uint32_t>(f));
  previous_ = f;
  anchor_ = gop_ == 0 || f + 1 >= frame_count_ ? f + 1 : std::min(f + gop_, frame_count_ - 1);
  return {static_cast<uint32_t>(f)};
}

LccFrame lcc_frame(const Vec3& a, const Vec3& b, const Vec3& c) {
  LccFrame frame;
  frame.origin = {(b.x + c.x) * 0.5, (b.y + c.y) * 0.5, (b.z + c.z) * 0.5};
  // A zero edge takes the axis x of the space; a triangle without a normal
  // takes the unit normal of z and the axis of the space least aligned
  // with z (the lowest such axis on a tie).
  if (!normalized(c - b, frame.z)) frame.z = {1, 0, 0};
  if (!normalized(cross(b - a, c - a), frame.y)) {
    const double ax = std::fabs(frame.z.x), ay = std::fabs(frame.z.y), az = std::fabs(frame.z.z);
    const Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0} : ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
    normalized(cross(frame.z, axis), frame.y);
  }
  frame.x = cross(frame.z, frame.y);
  return frame;
}

Cylindrical radius_and_height(const LccFrame& frame, const Vec3& p) {
  const Vec3 d = p - frame.origin;
  const double x = dot(d, frame.x), y = dot(d, frame.y);
  return {0, std::sqrt(x * x + y * y), dot(d, frame.z)};
}

Cylindrical to_cylindrical(const LccFrame& frame, const Vec3& p) {
  const Vec3 d = p - frame.origin;
  const double x = dot(d, frame.x), y = dot(d, frame.y);
  return {angle_of(y, x), std::sqrt(x * x + y * y), dot(d, frame.z)};
}

Vec3 from_cylindrical(const LccFrame& frame, double cos_theta, double sin_theta, double radius, double height) {
  const double u = radius * cos_theta, v = radius * sin_theta;
  return {frame.origin.x + u * frame.x.x + v * frame.y.x + height * frame.z.x,
          frame.origin.y + u * frame.x.y + v * frame.y.y + height * frame.z.y,
          frame.origin.z + u * frame.x.z + v * frame.y.z + height * frame.z.z};
}

AngleTable::AngleTable(int bits) {
  // 2π·k/N through octants: x = 2π·j/N with j ≤ N/8 by the symmetries of
  // the quadrant, then the quadrant's rotation; N = 2^bits ≥ 8.
  constexpr double kTwoPi = 6.283185307179586;
  const int64_t n = int64_t{1} << bits, quarter = n / 4, eighth = n / 8;
  cos_.resize(static_cast<size_t>(n));
  sin_.resize(static_cast<size_t>(n));
  for (int64_t index = 0; index < n; ++index) {
    const int64_t m = ((index - n / 2) % n + n) % n;  // the angle's k, modulo N
    const int64_t q = m / quarter, j = m % quarter;
    double s, c;
    if (j <= eighth) {
      sin_cos(kTwoPi * static_cast<double>(j) / static_cast<double>(n), s, c);
    } else {
      sin_cos(kTwoPi * static_cast<double>(quarter - j) / static_cast<double>(n), c, s);
    }
    const double cos_q[4] = {c, -s, -c, s}, sin_q[4] = {s, c, -s, -c};
    cos_[static_cast<size_t>(index)] = cos_q[q];
    sin_[static_cast<size_t>(index)] = sin_q[q];
  }
}

Vec3 lcc_grid_position(const LccHeader& header, const IntPoint3& q) {
  return {static_cast<double>(header.origin_value(0)) + static_cast<double>(q[0]) * static_cast<double>(header.step_value(0)),
          static_cast<double>(header.origin_value(1)) + static_cast<double>(q[1]) * static_cast<double>(header.step_value(1)),
          static_cast<double>(header.origin_value(2)) + static_cast<double>(q[2]) * static_cast<double>(header.step_value(2))};
}

double average_edge_length(std::span<const Triangle> faces, std::span<const Vec3> positions) {
  double sum = 0;
  for (const Triangle& t : faces)
    for (int e = 0; e < 3; ++e) {
      const Vec3 d = positions[t.v[(e + 1) % 3]] - positions[t.v[e]];
      sum += std::sqrt(dot(d, d));
    }
  const double length = faces.empty() ? 0 : sum / static_cast<double>(3 * faces.size());
  return length > 0 && std::isfinite(length) ? length : 1;
}

LccModel::LccModel(std::span<const Triangle> faces, std::span<const Vec3> reference, int theta_bits, int rh_bits, double rh_range)
    : order_(lcc_order(faces, reference.size())),
      edge_length_(average_edge_length(faces, reference)),
      theta_limit_(int32_t{1} << theta_bits),
      rh_limit_(int32_t{1} << rh_bits),
      rh_step_(rh_range / static_cast<double>(int64_t{1} << rh_bits)),
      angles_(theta_bits + 1) {
  pair_steps(reference.size());
  reference_radius_.reserve(order_.steps.size());
  reference_height_.reserve(order_.steps.size());
  for (const LccStep& step : order_.steps) {
    const Cylindrical c = radius_and_height(lcc_frame(reference[step.a], reference[step.b], reference[step.c]), reference[step.d]);
    reference_radius_.push_back(c.radius / edge_length_);
    reference_height_.push_back(c.height / edge_length_);
  }
}

// Within a chunk, a step's depth is one more than the deepest of the
// chunk's steps it waits for; steps of one depth are paired in order.
void LccModel::pair_steps(size_t vertex_count) {
  std::vector<uint32_t> depth_of_vertex(vertex_count, 0), depth(kLccStepChunk), start, by_depth(kLccStepChunk);
  for (size_t first = 0; first < order_.steps.size(); first += kLccStepChunk) {
    const size_t end = std::min(first + kLccStepChunk, order_.steps.size());
    start.assign(end - first + 2, 0);
    for (size_t k = first; k < end; ++k) {
      const LccStep& s = order_.steps[k];
      depth[k - first] = 1 + std::max({depth_of_vertex[s.a], depth_of_vertex[s.b], depth_of_vertex[s.c]});
      depth_of_vertex[s.d] = depth[k - first];
      ++start[depth[k - first] + 1];
    }
    for (size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    for (size_t k = first; k < end; ++k) by_depth[start[depth[k - first]]++] = static_cast<uint32_t>(k);
    chunk_pairs_.push_back(static_cast<uint32_t>(pairs_.size()));
    for (size_t i = 0; i < end - first;) {
      const uint32_t k = by_depth[i];
      const bool paired = i + 1 < end - first && depth[by_depth[i + 1] - first] == depth[k - first];
      pairs_.push_back({k, paired ? by_depth[i + 1] : StepPair::kAlone});
      i += paired ? 2 : 1;
    }
    for (size_t k = first; k < end; ++k) depth_of_vertex[order_.steps[k].d] = 0;
  }
  chunk_pairs_.push_back(static_cast<uint32_t>(pairs_.size()));
}

void LccModel::place_chunk(size_t chunk, std::span<const int32_t> indices, std::span<Vec3> positions) const {
  for (uint32_t i = chunk_pairs_[chunk]; i < chunk_pairs_[chunk + 1]; ++i) place_pair(pairs_[i], indices, positions);
}

void LccModel::place_pair(const StepPair& pair, std::span<const int32_t> indices, std::span<Vec3> positions) const {
  const auto alone = [&](uint32_t k) { positions[order_.steps[k].d] = place(k, positions, indices[3 * k], indices[3 * k + 1], indices[3 * k + 2]); };
#ifdef M4MESH_LCC_PAIRS
  if (pair.second != StepPair::kAlone) {
    // Lane 0 is the first step, lane 1 the second; each lane makes place()'s IEEE operations in place()'s order.
    const LccStep &s0 = order_.steps[pair.first], &s1 = order_.steps[pair.second];
    struct Lanes3 {
      __m128d x, y, z;
    };
    const auto load = [&](NodeIndex v0, NodeIndex v1) {
      return Lanes3{_mm_set_pd(positions[v1].x, positions[v0].x), _mm_set_pd(positions[v1].y, positions[v0].y), _mm_set_pd(positions[v1].z, positions[v0].z)};
    };
    const auto sub = [](const Lanes3& l, const Lanes3& r) { return Lanes3{_mm_sub_pd(l.x, r.x), _mm_sub_pd(l.y, r.y), _mm_sub_pd(l.z, r.z)}; };
    const auto cross3 = [](const Lanes3& l, const Lanes3& r) {
      return Lanes3{_mm_sub_pd(_mm_mul_pd(l.y, r.z), _mm_mul_pd(l.z, r.y)), _mm_sub_pd(_mm_mul_pd(l.z, r.x), _mm_mul_pd(l.x, r.z)),
                    _mm_sub_pd(_mm_mul_pd(l.x, r.y), _mm_mul_pd(l.y, r.x))};
    };
    const auto dot3 = [](const Lanes3& l, const Lanes3& r) {
      return _mm_add_pd(_mm_add_pd(_mm_mul_pd(l.x, r.x), _mm_mul_pd(l.y, r.y)), _mm_mul_pd(l.z, r.z));
    };
    const Lanes3 a = load(s0.a, s1.a), b = load(s0.b, s1.b), c = load(s0.c, s1.c);
    const Lanes3 edge = sub(c, b), normal = cross3(sub(b, a), sub(c, a));
    const __m128d edge_length = _mm_sqrt_pd(dot3(edge, edge)), normal_length = _mm_sqrt_pd(dot3(normal, normal));
    const __m128d zero = _mm_setzero_pd();
    if (_mm_movemask_pd(_mm_and_pd(_mm_cmpgt_pd(edge_length, zero), _mm_cmpgt_pd(normal_length, zero))) == 3) {
      const Lanes3 z{_mm_div_pd(edge.x, edge_length), _mm_div_pd(edge.y, edge_length), _mm_div_pd(edge.z, edge_length)};
      const Lanes3 y{_mm_div_pd(normal.x, normal_length), _mm_div_pd(normal.y, normal_length), _mm_div_pd(normal.z, normal_length)};
      const Lanes3 x = cross3(z, y);
      const __m128d half = _mm_set1_pd(0.5);
      const Lanes3 origin{_mm_mul_pd(_mm_add_pd(b.x, c.x), half), _mm_mul_pd(_mm_add_pd(b.y, c.y), half), _mm_mul_pd(_mm_add_pd(b.z, c.z), half)};
      const uint32_t k0 = pair.first, k1 = pair.second;
      const size_t angle0 = static_cast<size_t>(indices[3 * k0] + theta_limit_), angle1 = static_cast<size_t>(indices[3 * k1] + theta_limit_);
      const __m128d step = _mm_set1_pd(rh_step_), length = _mm_set1_pd(edge_length_);
      const __m128d rho = _mm_set_pd(static_cast<double>(indices[3 * k1 + 1]), static_cast<double>(indices[3 * k0 + 1]));
      const __m128d zeta = _mm_set_pd(static_cast<double>(indices[3 * k1 + 2]), static_cast<double>(indices[3 * k0 + 2]));
      const __m128d radius = _mm_mul_pd(_mm_add_pd(_mm_mul_pd(rho, step), _mm_set_pd(reference_radius_[k1], reference_radius_[k0])), length);
      const __m128d height = _mm_mul_pd(_mm_add_pd(_mm_mul_pd(zeta, step), _mm_set_pd(reference_height_[k1], reference_height_[k0])), length);
      const __m128d u = _mm_mul_pd(radius, _mm_set_pd(angles_.cos(angle1), angles_.cos(angle0)));
      const __m128d v = _mm_mul_pd(radius, _mm_set_pd(angles_.sin(angle1), angles_.sin(angle0)));
      const auto axis = [&](__m128d o, __m128d xa, __m128d ya, __m128d za) {
        return _mm_add_pd(_mm_add_pd(_mm_add_pd(o, _mm_mul_pd(u, xa)), _mm_mul_pd(v, ya)), _mm_mul_pd(height, za));
      };
      const __m128d px = axis(origin.x, x.x, y.x, z.x), py = axis(origin.y, x.y, y.y, z.y), pz = axis(origin.z, x.z, y.z, z.z);
      positions[s0.d] = {_mm_cvtsd_f64(px), _mm_cvtsd_f64(py), _mm_cvtsd_f64(pz)};
      positions[s1.d] = {_mm_cvtsd_f64(_mm_unpackhi_pd(px, px)), _mm_cvtsd_f64(_mm_unpackhi_pd(py, py)), _mm_cvtsd_f64(_mm_unpackhi_pd(pz, pz))};
      return;
    }
  }
#endif
  alone(pair.first);
  if (pair.second != StepPair::kAlone) alone(pair.second);
}

Vec3 LccModel::place_in(const LccFrame& frame, size_t k, int32_t theta, int32_t rho, int32_t zeta) const {
  const size_t angle = static_cast<size_t>(theta + theta_limit_);
  const double radius = (static_cast<double>(rho) * rh_step_ + reference_radius_[k]) * edge_length_;
  const double height = (static_cast<double>(zeta) * rh_step_ + reference_height_[k]) * edge_length_;
  return from_cylindrical(frame, angles_.cos(angle), angles_.sin(angle), radius, height);
}

LccPredictor::LccPredictor(const LccHeader& header, const LccOrder& order, std::span<const IntPoint3> reference_grid)
    : download_(header.mode == kLccDownloadMode), theta_limit_(int32_t{1} << header.theta_bits) {
  for (NodeIndex v : order.direct)
    for (int axis = 0; axis < 3; ++axis) reference_.direct.push_back(reference_grid[v][axis]);
  reference_.steps.assign(3 * order.steps.size(), 0);
}

const LccIndices& LccPredictor::predict(const LccCodedFrame& coded) {
  if (coded.anchor()) {
    prediction_.direct = download_ && !window_.empty() ? window_.back().direct : reference_.direct;
    prediction_.steps = reference_.steps;
    return prediction_;
  }
  const LccIndices &l = kept(coded.left), &r = kept(coded.right);
  auto mean = [](int32_t a, int32_t b) { return static_cast<int32_t>((int64_t{a} + b) >> 1); };
  prediction_.direct.resize(l.direct.size());
  for (size_t i = 0; i < l.direct.size(); ++i) prediction_.direct[i] = mean(l.direct[i], r.direct[i]);
  prediction_.steps.resize(l.steps.size());
  for (size_t i = 0; i < l.steps.size(); i += 3) {
    const int32_t arc = lcc_wrapped_angle(int64_t{r.steps[i]} - l.steps[i], theta_limit_);
    prediction_.steps[i] = lcc_wrapped_angle(int64_t{l.steps[i]} + (arc >> 1), theta_limit_);
    prediction_.steps[i + 1] = mean(l.steps[i + 1], r.steps[i + 1]);
    prediction_.steps[i + 2] = mean(l.steps[i + 2], r.steps[i + 2]);
  }
  return prediction_;
}

const LccIndices& LccPredictor::kept(uint32_t frame) const {
  if (frame < window_start_ || frame - window_start_ >= window_.size() || (window_[frame - window_start_].direct.empty() && window_[frame - window_start_].steps.empty()))
    throw Error(ErrorKind::kStructure, "frame_index", frame, kNoOffset, "a frame predicted from frame " + std::to_string(frame) + ", which is not kept");
  return window_[frame - window_start_];
}

void LccPredictor::keep(const LccCodedFrame& coded, LccIndices indices) {
  if (coded.anchor()) {
    // The window becomes [previous anchor, this anchor]; the previous
    // anchor is the last slot.
    if (!window_.empty()) {
      if (window_.size() > 1) window_.front() = std::move(window_.back());
      window_.resize(1);
      window_start_ = last_anchor_;
    } else {
      window_start_ = coded.frame;
    }
    last_anchor_ = coded.frame;
  }
  const size_t slot = coded.frame - window_start_;
  if (window_.size() <= slot) window_.resize(slot + 1);
  window_[slot] = std::move(indices);
}

}  // namespace m4mesh
