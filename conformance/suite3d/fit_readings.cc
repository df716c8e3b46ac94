// The affine fit read in other orders, and values that tell the readings apart.
#include "conformance/suite3d/fit_readings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mesh3d/affine_fit.h"

namespace m4mesh::suite3d {

namespace {

__extension__ typedef __int128 Wide;

// The exact fit c = Σ w[i] x[i] / d as integers: d = n det A and w, with
// A = 256 n C the ridge's normal equations scaled to integers.
struct ExactFit {
  std::vector<Wide> w;
  Wide d = 0;
};

ExactFit exact_fit(std::span<const std::array<int32_t, 3>> q) {
  const Wide n = static_cast<Wide>(q.size());
  Wide s[3] = {}, m[3][3] = {};
  for (const auto& p : q)
    for (int a = 0; a < 3; ++a) {
      s[a] += p[a];
      for (int c = 0; c < 3; ++c) m[a][c] += Wide{p[a]} * p[c];
    }
  const Wide trace = m[0][0] + m[1][1] + m[2][2];
  Wide A[3][3];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) A[a][c] = 256 * n * m[a][c] - 256 * s[a] * s[c] + (a == c ? n * trace : 0);
  Wide adj[3][3];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      const int r0 = (c + 1) % 3, r1 = (c + 2) % 3, k0 = (a + 1) % 3, k1 = (a + 2) % 3;
      adj[a][c] = A[r0][k0] * A[r1][k1] - A[r0][k1] * A[r1][k0];
    }
  const Wide det = A[0][0] * adj[0][0] + A[0][1] * adj[1][0] + A[0][2] * adj[2][0];
  ExactFit fit;
  fit.d = n * det;
  for (const auto& p : q) {
    Wide rho[3], slope = 0;
    for (int a = 0; a < 3; ++a) rho[a] = 256 * n * p[a] - 256 * s[a];
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) slope += s[a] * adj[a][c] * rho[c];
    fit.w.push_back(det - slope);
  }
  return fit;
}

// m4mesh's fit of the vertex at the origin from the points q with values x.
int64_t fit_by_m4mesh(std::span<const std::array<int32_t, 3>> q, std::span<const int32_t> x) {
  std::vector<IntPoint3> positions(1);
  std::vector<uint32_t> points;
  for (const auto& p : q) {
    points.push_back(static_cast<uint32_t>(positions.size()));
    positions.push_back({p[0], p[1], p[2]});
  }
  std::array<int64_t, 1> prediction;
  affine_fit<1>(positions, 0, points, [&](uint32_t u) { return std::array<int32_t, 1>{x[u - 1]}; }, prediction);
  return prediction[0];
}

// A short basis (LLL-reduced, δ = 0.99) of the values x whose exact fit is
// an integer, Σ w[i] x[i] ≡ 0 (mod d): the lattice of rows (e_i, K w[i])
// and (0, K d) reduced, its rows whose last entry is 0.
std::vector<std::vector<Wide>> integer_fits(const ExactFit& fit) {
  const size_t n = fit.w.size(), m = n + 1;
  constexpr Wide kWeight = Wide{1} << 20;
  std::vector<std::vector<Wide>> b(m, std::vector<Wide>(m));
  for (size_t i = 0; i < n; ++i) b[i][i] = 1, b[i][n] = kWeight * (fit.w[i] % fit.d);
  b[n][n] = kWeight * fit.d;
  using Real = long double;
  std::vector<std::vector<Real>> mu(m, std::vector<Real>(m));
  std::vector<Real> norm(m);
  const auto gram_schmidt = [&] {
    std::vector<std::vector<Real>> star(m, std::vector<Real>(m));
    for (size_t i = 0; i < m; ++i) {
      for (size_t k = 0; k < m; ++k) star[i][k] = static_cast<Real>(b[i][k]);
      for (size_t j = 0; j < i; ++j) {
        Real dot = 0;
        for (size_t k = 0; k < m; ++k) dot += static_cast<Real>(b[i][k]) * star[j][k];
        mu[i][j] = dot / norm[j];
        for (size_t k = 0; k < m; ++k) star[i][k] -= mu[i][j] * star[j][k];
      }
      norm[i] = 0;
      for (size_t k = 0; k < m; ++k) norm[i] += star[i][k] * star[i][k];
    }
  };
  gram_schmidt();
  for (size_t k = 1; k < m;) {
    for (size_t j = k; j-- > 0;) {
      const Wide r = static_cast<Wide>(std::llround(mu[k][j]));
      if (r == 0) continue;
      for (size_t i = 0; i < m; ++i) b[k][i] -= r * b[j][i];
      gram_schmidt();
    }
    if (norm[k] >= (0.99L - mu[k][k - 1] * mu[k][k - 1]) * norm[k - 1]) {
      ++k;
    } else {
      std::swap(b[k], b[k - 1]);
      gram_schmidt();
      k = std::max<size_t>(k - 1, 1);
    }
  }
  std::vector<std::vector<Wide>> rows;
  for (auto& row : b)
    if (row[n] == 0) rows.emplace_back(row.begin(), row.end() - 1);
  return rows;
}

}  // namespace

int64_t fit_as_read(std::span<const std::array<int32_t, 3>> q, std::span<const int32_t> x, FitReading reading) {
  using enum FitReading;
  int64_t S[3] = {}, M[3][3] = {}, B = 0, T[3] = {};
  for (size_t i = 0; i < q.size(); ++i) {
    B += x[i];
    for (int a = 0; a < 3; ++a) {
      S[a] += q[i][a];
      T[a] += int64_t{q[i][a]} * x[i];
      for (int c = 0; c < 3; ++c) M[a][c] += int64_t{q[i][a]} * q[i][c];
    }
  }
  const auto real = [](int64_t v) { return static_cast<double>(v); };
  const double n = static_cast<double>(q.size());
  double C[3][3];
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      C[a][c] = reading == kMeanFirstInMatrix ? real(M[a][c]) - real(S[a]) * (real(S[c]) / n) : real(M[a][c]) - real(S[a]) * real(S[c]) / n;
  const double ridge = kAffineFitRidge * real(M[0][0] + M[1][1] + M[2][2]);
  for (int a = 0; a < 3; ++a) C[a][a] += ridge;
  double c0, c1, c2, det;
  if (reading == kFused) {
    c0 = std::fma(C[1][1], C[2][2], -(C[1][2] * C[1][2]));
    c1 = std::fma(C[0][1], C[2][2], -(C[1][2] * C[0][2]));
    c2 = std::fma(C[0][1], C[1][2], -(C[1][1] * C[0][2]));
    det = std::fma(C[0][2], c2, std::fma(C[0][0], c0, -(C[0][1] * c1)));
  } else {
    c0 = C[1][1] * C[2][2] - C[1][2] * C[1][2];
    c1 = C[0][1] * C[2][2] - C[1][2] * C[0][2];
    c2 = C[0][1] * C[1][2] - C[1][1] * C[0][2];
    if (reading == kSarrusDeterminant)
      det = C[0][0] * C[1][1] * C[2][2] + C[0][1] * C[1][2] * C[2][0] + C[0][2] * C[1][0] * C[2][1] - C[0][2] * C[1][1] * C[2][0] -
            C[0][0] * C[1][2] * C[2][1] - C[0][1] * C[1][0] * C[2][2];
    else if (reading == kDeterminantRightFirst)
      det = C[0][0] * c0 - (C[0][1] * c1 - C[0][2] * c2);
    else
      det = (C[0][0] * c0 - C[0][1] * c1) + C[0][2] * c2;
  }
  double g[3] = {};
  if (det > 0) {
    double r[3];
    for (int a = 0; a < 3; ++a) r[a] = reading == kMeanFirstInResidual ? real(T[a]) - real(S[a]) * (real(B) / n) : real(T[a]) - real(S[a]) * real(B) / n;
    if (reading == kCofactorSolve) {
      const double a01 = C[0][2] * C[1][2] - C[0][1] * C[2][2], a02 = C[0][1] * C[1][2] - C[0][2] * C[1][1];
      const double a11 = C[0][0] * C[2][2] - C[0][2] * C[0][2], a12 = C[0][2] * C[0][1] - C[0][0] * C[1][2];
      const double a22 = C[0][0] * C[1][1] - C[0][1] * C[0][1];
      g[0] = (c0 * r[0] + a01 * r[1] + a02 * r[2]) / det;
      g[1] = (a01 * r[0] + a11 * r[1] + a12 * r[2]) / det;
      g[2] = (a02 * r[0] + a12 * r[1] + a22 * r[2]) / det;
    } else {
      g[0] = ((r[0] * c0 - C[0][1] * (r[1] * C[2][2] - C[1][2] * r[2])) + C[0][2] * (r[1] * C[1][2] - C[1][1] * r[2])) / det;
      g[1] = ((C[0][0] * (r[1] * C[2][2] - C[1][2] * r[2]) - r[0] * c1) + C[0][2] * (C[0][1] * r[2] - r[1] * C[0][2])) / det;
      g[2] = ((C[0][0] * (C[1][1] * r[2] - r[1] * C[1][2]) - C[0][1] * (C[0][1] * r[2] - r[1] * C[0][2])) + r[0] * c2) / det;
    }
  }
  const double slope = reading == kSlopeSumRightFirst ? g[0] * real(S[0]) + (g[1] * real(S[1]) + g[2] * real(S[2]))
                                                      : (g[0] * real(S[0]) + g[1] * real(S[1])) + g[2] * real(S[2]);
  const double c = reading == kMeanMinusSlope ? real(B) / n - slope / n : (real(B) - slope) / n;
  return static_cast<int64_t>(std::floor(std::fmin(std::fmax(c, -kAffineFitLimit), kAffineFitLimit)));
}

std::optional<std::vector<int32_t>> values_telling_apart(std::span<const std::array<int32_t, 3>> q, FitReading reading, SplitMix64& random,
                                                         int tries) {
  for (const auto& p : q)
    for (const int32_t a : p)
      if (std::abs(a) > 16 || q.size() > 16) throw std::logic_error("values_telling_apart: points beyond ±16 or more than 16 of them");
  const ExactFit fit = exact_fit(q);
  if (fit.d == 0) return std::nullopt;  // every point at v's position: the mean, in every reading
  const std::vector<std::vector<Wide>> lattice = integer_fits(fit);
  constexpr int32_t kLimit = 1 << 15;
  for (int t = 0; t < tries; ++t) {
    std::vector<Wide> sum(q.size());
    for (const auto& row : lattice) {
      const int32_t k = random.uniform(-4, 4);
      for (size_t i = 0; i < q.size(); ++i) sum[i] += k * row[i];
    }
    std::vector<int32_t> x;
    Wide c = 0;
    for (size_t i = 0; i < q.size(); ++i) {
      if (sum[i] < -kLimit || sum[i] > kLimit) break;
      x.push_back(static_cast<int32_t>(sum[i]));
      c += fit.w[i] * sum[i];
    }
    if (x.size() < q.size() || c % fit.d != 0 || c / fit.d <= -kLimit || c / fit.d >= kLimit) continue;
    const int64_t text = fit_as_read(q, x, FitReading::kText);
    if (text != fit_by_m4mesh(q, x)) throw std::logic_error("values_telling_apart: the text's reading is not m4mesh's fit");
    if (fit_as_read(q, x, reading) != text) return x;
  }
  return std::nullopt;
}

}  // namespace m4mesh::suite3d
