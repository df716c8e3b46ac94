// Grey pictures for motion estimation. Coordinates are continuous pixels:
// pixel (i, j) covers [i, i + 1) × [j, j + 1), so its centre is at
// (i + ½, j + ½) and a mesh node at X half pixels lies at X / 2 (as
// render/texture_warp.h draws it).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace m4mesh {

struct Luma {
  uint32_t width = 0, height = 0;
  std::vector<float> values;  // row by row from the top

  Luma() = default;
  Luma(uint32_t w, uint32_t h, float fill = 0) : width(w), height(h), values(size_t{w} * h, fill) {}
  float& at(uint32_t x, uint32_t y) { return values[size_t{y} * width + x]; }
  float at(uint32_t x, uint32_t y) const { return values[size_t{y} * width + x]; }

  // Bilinear between pixel centres, the edge pixels repeated outside.
  float sample(double x, double y) const {
    const double u = std::clamp(x - 0.5, 0.0, width - 1.0), v = std::clamp(y - 0.5, 0.0, height - 1.0);
    const auto x0 = static_cast<uint32_t>(u), y0 = static_cast<uint32_t>(v);
    const uint32_t x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
    const auto fx = static_cast<float>(u - x0), fy = static_cast<float>(v - y0);
    const float top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
    const float bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
    return top + (bottom - top) * fy;
  }
};

// Half the size, each pixel the mean of the 2 × 2 it covers (an odd last
// row or column is dropped): coordinates halve exactly.
Luma halved(const Luma& picture);

// picture, halved, halved again …: `levels` + 1 pictures, finest first.
std::vector<Luma> pyramid(const Luma& picture, int levels);

// PSNR in dB of b against a (peak 255) over the pixels where `counted` is
// non-zero (all when empty); +inf when they agree.
double psnr(const Luma& a, const Luma& b, const std::vector<uint8_t>& counted = {});

// A window to match: each pixel's offset from the point matched, and the
// value it should find there.
using Window = std::vector<std::array<double, 3>>;

// The window's position of least squared difference in the picture near
// `from`, by Gauss–Newton steps on the picture's bilinear samples (the
// Lucas–Kanade fit); none where the window's gradients do not fix both
// axes or the fit leaves `from` by over 0.75 pixels.
std::optional<std::array<double, 2>> subpixel_fit(const Luma& picture, const Window& window, const std::array<double, 2>& from);

}  // namespace m4mesh
