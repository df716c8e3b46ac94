// The affine fit of docs/codec_cpca_wpt.md ("Prediction by the mean
// shape"): a vertex's values predicted by the affine
// function of the mean shape's positions that best fits the known vertices
// around it, a small ridge keeping the function flat where they do not
// settle it. A rigid part's trajectories are affine in its rest positions,
// so the bases of its components are too. Exact integer sums, then
// binary64 +, −, ×, / in the order written (no contraction), so that every
// decoder agrees.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh3d/mesh_predictor.h"

namespace m4mesh {

inline constexpr double kAffineFitRidge = 1.0 / 256;  // λ: the ridge's share of the points' spread
inline constexpr double kAffineFitLimit = 32768;       // the prediction lies within ±2^15, as the values do (kCpcaMaxBasis)
inline constexpr int kAffineFitBits = 11;              // the positions' differences are shifted into ±2^11

// The vertices the fit of v uses: its known corners and the known apexes of
// its parallelograms, each once, in increasing index. Returns the channel:
// kParallelogramChannel when an apex is known, kNeighbourChannel when only
// corners are, −1 when none is.
template <class Known>
int affine_fit_support(const MeshPredictor& predictor, uint32_t v, Known known, std::vector<uint32_t>& points) {
  points.clear();
  predictor.for_each_known_corner(v, known, [&](uint32_t u) { points.push_back(u); });
  const size_t corners = points.size();
  predictor.for_each_parallelogram(v, known, [&](uint32_t, uint32_t, uint32_t z) {
    if (known(z)) points.push_back(z);
  });
  const bool parallelogram = points.size() > corners;
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return parallelogram ? syntax::kParallelogramChannel : points.empty() ? -1 : syntax::kNeighbourChannel;
}

// What the fit of v takes from the positions alone, so that it is found
// once for every set of values fitted there: the points' differences to
// v's position, shifted right so that they fit in 11 bits (q, one per
// point; the sums below are then exact integers, whatever their order),
// and the centred normal equations' terms.
struct AffineFitShape {
  double n = 0;
  int64_t s[3] = {};
  double C[3][3] = {};
  double c0 = 0, c1 = 0, c2 = 0, det = 0;
};

inline AffineFitShape affine_fit_shape(std::span<const IntPoint3> positions, uint32_t v, std::span<const uint32_t> points,
                                       std::span<std::array<int32_t, 3>> q) {
  int64_t largest = 0;
  for (const uint32_t u : points)
    for (int a = 0; a < 3; ++a) largest = std::max(largest, std::abs(int64_t{positions[u][a]} - positions[v][a]));
  const int shift = std::max(0, static_cast<int>(std::bit_width(static_cast<uint64_t>(largest))) - kAffineFitBits);
  AffineFitShape f;
  int64_t m[3][3] = {};
  for (size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) q[i][a] = static_cast<int32_t>((int64_t{positions[points[i]][a]} - positions[v][a]) >> shift);
    for (int a = 0; a < 3; ++a) {
      f.s[a] += q[i][a];
      for (int c = a; c < 3; ++c) m[a][c] += int64_t{q[i][a]} * q[i][c];
    }
  }
  f.n = static_cast<double>(points.size());
  const auto real = [](int64_t x) { return static_cast<double>(x); };
  for (int a = 0; a < 3; ++a)
    for (int c = a; c < 3; ++c) f.C[a][c] = f.C[c][a] = real(m[a][c]) - real(f.s[a]) * real(f.s[c]) / f.n;
  const double ridge = kAffineFitRidge * real(m[0][0] + m[1][1] + m[2][2]);
  for (int a = 0; a < 3; ++a) f.C[a][a] += ridge;
  const double(&C)[3][3] = f.C;
  f.c0 = C[1][1] * C[2][2] - C[1][2] * C[1][2];
  f.c1 = C[0][1] * C[2][2] - C[1][2] * C[0][2];
  f.c2 = C[0][1] * C[1][2] - C[1][1] * C[0][2];
  f.det = C[0][0] * f.c0 - C[0][1] * f.c1 + C[0][2] * f.c2;
  return f;
}

// The fit's value at v of each of the D values per vertex, floored, from
// the points' values (value(u): D integers) and their shape: the least
// squares of b = c + g · (P − P_v) with the ridge λ (Σ |P − P_v|²) |g|²,
// solved centred by Cramer's rule; g = 0 when the determinant is not
// positive (every point at v's position).
template <size_t D, class Value>
void affine_fit_values(const AffineFitShape& f, std::span<const uint32_t> points, std::span<const std::array<int32_t, 3>> q, Value value,
                       std::array<int64_t, D>& p) {
  int64_t b[D] = {}, t[D][3] = {};
  for (size_t i = 0; i < points.size(); ++i) {
    const auto& values = value(points[i]);
    for (size_t d = 0; d < D; ++d) {
      b[d] += values[d];
      for (int a = 0; a < 3; ++a) t[d][a] += int64_t{q[i][a]} * values[d];
    }
  }
  const auto real = [](int64_t x) { return static_cast<double>(x); };
  const double(&C)[3][3] = f.C;
  for (size_t d = 0; d < D; ++d) {
    double g[3] = {};
    if (f.det > 0) {
      double r[3];
      for (int a = 0; a < 3; ++a) r[a] = real(t[d][a]) - real(f.s[a]) * real(b[d]) / f.n;
      g[0] = (r[0] * f.c0 - C[0][1] * (r[1] * C[2][2] - C[1][2] * r[2]) + C[0][2] * (r[1] * C[1][2] - C[1][1] * r[2])) / f.det;
      g[1] = (C[0][0] * (r[1] * C[2][2] - C[1][2] * r[2]) - r[0] * f.c1 + C[0][2] * (C[0][1] * r[2] - r[1] * C[0][2])) / f.det;
      g[2] = (C[0][0] * (C[1][1] * r[2] - r[1] * C[1][2]) - C[0][1] * (C[0][1] * r[2] - r[1] * C[0][2]) + r[0] * f.c2) / f.det;
    }
    const double c = (real(b[d]) - (g[0] * real(f.s[0]) + g[1] * real(f.s[1]) + g[2] * real(f.s[2]))) / f.n;
    p[d] = static_cast<int64_t>(std::floor(std::fmin(std::fmax(c, -kAffineFitLimit), kAffineFitLimit)));
  }
}

// Both at once, for one set of values.
template <size_t D, class Value>
void affine_fit(std::span<const IntPoint3> positions, uint32_t v, std::span<const uint32_t> points, Value value, std::array<int64_t, D>& p) {
  std::vector<std::array<int32_t, 3>> q(points.size());
  const AffineFitShape f = affine_fit_shape(positions, v, points, q);
  affine_fit_values<D>(f, points, q, value, p);
}

}  // namespace m4mesh
