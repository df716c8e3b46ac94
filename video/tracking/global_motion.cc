#include "video/tracking/global_motion.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace m4mesh {

namespace {

constexpr size_t kMostSamples = 40000;  // reference pixels per level
constexpr int kIterations = 8;         // Gauss–Newton steps per level

struct Sample {
  double x, y;
  float value;
};

// Reference pixels with some gradient (flat ones say nothing), thinned to kMostSamples.
std::vector<Sample> samples_of(const Luma& picture) {
  std::vector<Sample> out;
  if (picture.width < 3 || picture.height < 3) return out;
  const size_t interior = size_t{picture.width - 2} * (picture.height - 2);
  const auto stride = static_cast<uint32_t>(std::max<size_t>(1, static_cast<size_t>(std::ceil(std::sqrt(double(interior) / kMostSamples)))));
  for (uint32_t y = 1; y + 1 < picture.height; y += stride)
    for (uint32_t x = 1; x + 1 < picture.width; x += stride) {
      const float gx = picture.at(x + 1, y) - picture.at(x - 1, y), gy = picture.at(x, y + 1) - picture.at(x, y - 1);
      if (std::abs(gx) + std::abs(gy) >= 2.0f) out.push_back({x + 0.5, y + 0.5, picture.at(x, y)});
    }
  return out;
}

bool inside(const Luma& picture, double x, double y) { return x >= 1 && y >= 1 && x <= picture.width - 1.0 && y <= picture.height - 1.0; }

// Scales a map between pyramid levels (coordinates times `factor`).
Affine scaled(Affine m, double factor) {
  m.a[4] *= factor, m.a[5] *= factor;
  return m;
}

// The translation (added to `guess`) of smallest mean absolute difference.
Affine searched(const std::vector<Sample>& samples, const Luma& frame, Affine guess, int range) {
  double best = std::numeric_limits<double>::max();
  std::array<double, 2> best_shift{0, 0};
  for (int dy = -range; dy <= range; ++dy)
    for (int dx = -range; dx <= range; ++dx) {
      double sum = 0;
      size_t count = 0;
      for (const Sample& s : samples) {
        const auto [x, y] = guess(s.x, s.y);
        if (!inside(frame, x + dx, y + dy)) continue;
        sum += std::abs(frame.sample(x + dx, y + dy) - s.value);
        ++count;
      }
      if (count < samples.size() / 3) continue;  // mostly out of the frame: no evidence
      const double mean = sum / static_cast<double>(count) + 1e-3 * (std::abs(dx) + std::abs(dy));
      if (mean < best) best = mean, best_shift = {double(dx), double(dy)};
    }
  guess.a[4] += best_shift[0], guess.a[5] += best_shift[1];
  return guess;
}

// Robust Gauss–Newton steps on one level.
Affine refined(const std::vector<Sample>& samples, const Luma& frame, Affine m) {
  std::vector<double> residuals;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    residuals.clear();
    for (const Sample& s : samples) {
      const auto [x, y] = m(s.x, s.y);
      if (inside(frame, x, y)) residuals.push_back(std::abs(frame.sample(x, y) - s.value));
    }
    if (residuals.size() < 12) return m;
    std::nth_element(residuals.begin(), residuals.begin() + static_cast<std::ptrdiff_t>(residuals.size() / 2), residuals.end());
    const double k = 1.345 * std::max(1.0, 1.4826 * residuals[residuals.size() / 2]);  // Huber's threshold
    Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> right = Eigen::Matrix<double, 6, 1>::Zero();
    for (const Sample& s : samples) {
      const auto [x, y] = m(s.x, s.y);
      if (!inside(frame, x, y)) continue;
      const double r = frame.sample(x, y) - s.value;
      const double gx = 0.5 * (frame.sample(x + 1, y) - frame.sample(x - 1, y)), gy = 0.5 * (frame.sample(x, y + 1) - frame.sample(x, y - 1));
      const double w = std::abs(r) <= k ? 1.0 : k / std::abs(r);
      Eigen::Matrix<double, 6, 1> j;
      j << gx * s.x, gx * s.y, gy * s.x, gy * s.y, gx, gy;
      normal += w * j * j.transpose();
      right -= w * r * j;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(normal);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return m;
    const Eigen::Matrix<double, 6, 1> step = solver.solve(right);
    if (!step.allFinite()) return m;
    for (int i = 0; i < 6; ++i) m.a[static_cast<size_t>(i)] += step(i);
    if (std::abs(step(4)) + std::abs(step(5)) < 1e-3) break;
  }
  return m;
}

}  // namespace

Affine Affine::inverse() const {
  const double d = determinant();
  Affine m;
  m.a = {a[3] / d, -a[1] / d, -a[2] / d, a[0] / d, 0, 0};
  m.a[4] = -(m.a[0] * a[4] + m.a[1] * a[5]);
  m.a[5] = -(m.a[2] * a[4] + m.a[3] * a[5]);
  return m;
}

Affine Affine::after(const Affine& first) const {
  Affine m;
  m.a = {a[0] * first.a[0] + a[1] * first.a[2], a[0] * first.a[1] + a[1] * first.a[3], a[2] * first.a[0] + a[3] * first.a[2],
         a[2] * first.a[1] + a[3] * first.a[3], 0, 0};
  const auto [x, y] = (*this)(first.a[4], first.a[5]);
  m.a[4] = x, m.a[5] = y;
  return m;
}

Affine global_motion(const std::vector<Luma>& reference, const std::vector<Luma>& frame, const Affine& guess, uint32_t search) {
  const size_t levels = std::min(reference.size(), frame.size());
  if (levels == 0) return guess;
  const auto coarsest = static_cast<int>(levels - 1);
  const double coarse_scale = 1.0 / static_cast<double>(1 << coarsest);
  Affine m = scaled(guess, coarse_scale);
  for (int level = coarsest; level >= 0; --level) {
    const std::vector<Sample> samples = samples_of(reference[static_cast<size_t>(level)]);
    if (samples.size() < 64) return guess;  // too little structure to say
    const Luma& picture = frame[static_cast<size_t>(level)];
    if (level == coarsest) m = searched(samples, picture, m, static_cast<int>(std::ceil(search * coarse_scale)));
    m = refined(samples, picture, m);
    if (level > 0) m = scaled(m, 2.0);
  }
  return m.determinant() > 0.25 && m.determinant() < 4 ? m : guess;
}

}  // namespace m4mesh
