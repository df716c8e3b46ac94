// The quantization grid of the 3D codecs (docs/container3d.md), shared by
// encoders and decoders.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "common/point3.h"
#include "mesh3d/frame_source.h"
#include "mesh3d/sequence.h"

namespace m4mesh {

// Quantized coordinates stay within ±2^26 steps, so that motion residuals
// fit 32 bits with any prediction.
inline constexpr int64_t kMaxQuantized = int64_t{1} << 26;

// 2^(half / 2), the same on every platform (√2 correctly rounded, then an
// exact power of two).
double power_of_sqrt2(int half);

struct Grid {
  std::array<float, 3> origin{};
  std::array<float, 3> step{};

  // A grid of 2^bits − 1 steps per axis over the bounding box of `frame`
  // (an axis without extent borrows the largest one); with `equal_steps`,
  // every axis takes the step of the largest extent, so that grid units
  // are the same length on every axis.
  static Grid over(std::span<const Vec3> frame, int bits, bool equal_steps = false);
  // The same with 2^(half_bits / 2) − 1 steps: a grid between two of whole bits.
  static Grid over_half_bits(std::span<const Vec3> frame, int half_bits, bool equal_steps = false);
  // The grid over the first frame, unless a vertex of some frame lies
  // beyond ±kMaxQuantized steps on it: then the grid over every frame's box.
  static Grid covering(const FrameSource& source, int bits, bool equal_steps = false);

  // Decoding: origin + q · step in binary64, rounded to binary32.
  float position(int axis, int64_t q) const {
    return static_cast<float>(static_cast<double>(origin[axis]) + static_cast<double>(q) * static_cast<double>(step[axis]));
  }
  // Encoding (not normative): the nearest grid index; false if beyond ±kMaxQuantized.
  bool quantize(const Vec3& p, IntPoint3& q) const;
};

}  // namespace m4mesh
