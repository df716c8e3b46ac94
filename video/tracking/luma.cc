#include "video/tracking/luma.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace m4mesh {

Luma halved(const Luma& picture) {
  Luma half(std::max<uint32_t>(1, picture.width / 2), std::max<uint32_t>(1, picture.height / 2));
  for (uint32_t y = 0; y < half.height; ++y)
    for (uint32_t x = 0; x < half.width; ++x) {
      const uint32_t x0 = std::min(2 * x, picture.width - 1), x1 = std::min(2 * x + 1, picture.width - 1);
      const uint32_t y0 = std::min(2 * y, picture.height - 1), y1 = std::min(2 * y + 1, picture.height - 1);
      half.at(x, y) = (picture.at(x0, y0) + picture.at(x1, y0) + picture.at(x0, y1) + picture.at(x1, y1)) * 0.25f;
    }
  return half;
}

std::vector<Luma> pyramid(const Luma& picture, int levels) {
  std::vector<Luma> result{picture};
  for (int l = 0; l < levels; ++l) result.push_back(halved(result.back()));
  return result;
}

double psnr(const Luma& a, const Luma& b, const std::vector<uint8_t>& counted) {
  double sum = 0;
  size_t count = 0;
  for (size_t i = 0; i < a.values.size(); ++i) {
    if (!counted.empty() && !counted[i]) continue;
    const double d = static_cast<double>(a.values[i]) - b.values[i];
    sum += d * d;
    ++count;
  }
  if (count == 0 || sum == 0) return std::numeric_limits<double>::infinity();
  return 10 * std::log10(255.0 * 255.0 * static_cast<double>(count) / sum);
}

std::optional<std::array<double, 2>> subpixel_fit(const Luma& picture, const Window& window, const std::array<double, 2>& from) {
  constexpr int kSteps = 8;
  constexpr double kReach = 0.75, kConverged = 0.01;  // pixels
  std::array<double, 2> at = from;
  for (int step = 0; step < kSteps; ++step) {
    double hxx = 0, hxy = 0, hyy = 0, bx = 0, by = 0;
    for (const auto& [dx, dy, value] : window) {
      const double x = at[0] + dx, y = at[1] + dy;
      if (x < 1 || y < 1 || x > picture.width - 1.0 || y > picture.height - 1.0) continue;
      const double gx = picture.sample(x + 0.5, y) - picture.sample(x - 0.5, y);
      const double gy = picture.sample(x, y + 0.5) - picture.sample(x, y - 0.5);
      const double e = picture.sample(x, y) - value;
      hxx += gx * gx, hxy += gx * gy, hyy += gy * gy, bx += gx * e, by += gy * e;
    }
    const double det = hxx * hyy - hxy * hxy;
    if (!(det > 0)) return std::nullopt;
    const double ux = (hxy * by - hyy * bx) / det, uy = (hxy * bx - hxx * by) / det;
    at = {at[0] + ux, at[1] + uy};
    if (std::abs(at[0] - from[0]) > kReach || std::abs(at[1] - from[1]) > kReach) return std::nullopt;
    if (std::abs(ux) + std::abs(uy) < kConverged) break;
  }
  return at;
}

}  // namespace m4mesh
