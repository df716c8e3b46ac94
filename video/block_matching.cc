#include "video/block_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace m4mesh {

Luma luma_of(const Image& picture) {
  Luma luma(picture.width, picture.height);
  for (size_t i = 0; i < picture.pixels.size(); ++i) {
    const Rgb& p = picture.pixels[i];
    luma.values[i] = 0.299f * p.r + 0.587f * p.g + 0.114f * p.b;
  }
  return luma;
}

BlockPrediction block_prediction(const Image& previous, const Luma& previous_luma, const Luma& current_luma, uint32_t block, uint32_t range) {
  const uint32_t w = current_luma.width, h = current_luma.height;
  BlockPrediction result{Image(w, h), 0};
  const int r = static_cast<int>(range);
  for (uint32_t by = 0; by < h; by += block)
    for (uint32_t bx = 0; bx < w; bx += block) {
      const uint32_t x_end = std::min(bx + block, w), y_end = std::min(by + block, h);
      // Offsets in half pixels; whole pixels first, then the half-pixel ring.
      auto cost = [&](int hx, int hy, double bound) {
        double sum = 0;
        const bool whole = hx % 2 == 0 && hy % 2 == 0;
        for (uint32_t y = by; y < y_end && sum < bound; ++y)
          for (uint32_t x = bx; x < x_end; ++x) {
            const float predicted = whole ? previous_luma.at(static_cast<uint32_t>(std::clamp<int64_t>(int64_t{x} + hx / 2, 0, w - 1)),
                                                             static_cast<uint32_t>(std::clamp<int64_t>(int64_t{y} + hy / 2, 0, h - 1)))
                                          : previous_luma.sample(x + 0.5 + hx / 2.0, y + 0.5 + hy / 2.0);
            sum += std::abs(current_luma.at(x, y) - predicted);
          }
        return sum;
      };
      double best = std::numeric_limits<double>::max();
      int best_x = 0, best_y = 0;
      auto consider = [&](int hx, int hy) {
        const double c = cost(hx, hy, best);
        if (c < best || (c == best && std::abs(hx) + std::abs(hy) < std::abs(best_x) + std::abs(best_y))) best = c, best_x = hx, best_y = hy;
      };
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) consider(2 * dx, 2 * dy);
      const int centre_x = best_x, centre_y = best_y;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx != 0 || dy != 0) consider(centre_x + dx, centre_y + dy);
      for (uint32_t y = by; y < y_end; ++y)
        for (uint32_t x = bx; x < x_end; ++x) result.picture.at(x, y) = bilinear(previous, x + best_x / 2.0, y + best_y / 2.0);
      ++result.blocks;
    }
  return result;
}

}  // namespace m4mesh
