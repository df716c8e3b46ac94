// bfs3d (codec_id 1) syntax (docs/codec_bfs3d.md): the codec header, and a
// frame unit's data, six section lengths and per axis a section of bins
// and a section of raw bits holding the axis's motion residuals in coding
// order. One description for reading, writing, counting and tracing.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <span>

#include "common/bit_cast.h"
#include "syntax/io.h"
#include "syntax/mesh3d/grid.h"
#include "syntax/mesh3d/residual.h"

namespace m4mesh {

inline constexpr uint32_t kPredictAverage = 0;
inline constexpr uint32_t kPredictParallelogram = 1;

struct Bfs3dHeader {
  uint32_t bits = 12;  // quantization bits per coordinate over the first frame's box
  uint32_t prediction = kPredictAverage;
  std::array<uint32_t, 3> origin{};  // binary32 bit patterns
  std::array<uint32_t, 3> step{};

  float origin_value(int axis) const { return bit_cast<float>(origin[axis]); }
  float step_value(int axis) const { return bit_cast<float>(step[axis]); }
};

// A frame unit's data: the lengths, then bins x, raw x, bins y, raw y,
// bins z, raw z (raw bits MSB first, zero-padded to a byte).
struct Bfs3dFrame {
  std::array<uint32_t, 3> arithmetic_bytes{};
  std::array<uint32_t, 3> raw_bytes{};
  std::array<std::span<const uint8_t>, 3> bins;
  std::array<std::span<const uint8_t>, 3> raw;
};

namespace syntax {

inline constexpr const char* kAxisBins[3] = {"bins_x", "bins_y", "bins_z"};
inline constexpr const char* kAxisRaw[3] = {"raw_x", "raw_y", "raw_z"};
inline constexpr ResidualNames kMotionResidual = M4MESH_RESIDUAL_NAMES("motion", "motion_residual");

template <class IO>
void describe(IO& io, Bfs3dHeader& h) {
  io.field_in("quantization_bits", 8, h.bits, 4, 24);
  io.field_in("prediction_mode", 8, h.prediction, kPredictAverage, kPredictParallelogram);
  describe_grid(io, h.origin, h.step);
}

template <class IO>
void describe(IO& io, Bfs3dFrame& f) {
  static const char* const kArithmetic[3] = {"arithmetic_bytes_x", "arithmetic_bytes_y", "arithmetic_bytes_z"};
  static const char* const kRaw[3] = {"raw_bytes_x", "raw_bytes_y", "raw_bytes_z"};
  uint64_t total = 0;
  for (int axis = 0; axis < 3; ++axis) {
    io.field(kArithmetic[axis], 32, f.arithmetic_bytes[axis]);
    io.field(kRaw[axis], 32, f.raw_bytes[axis]);
    total += uint64_t{f.arithmetic_bytes[axis]} + f.raw_bytes[axis];
  }
  io.require_remaining_bytes("raw_bytes_z", total);
  for (int axis = 0; axis < 3; ++axis) {
    io.section(kAxisBins[axis], f.arithmetic_bytes[axis], f.bins[axis]);
    io.section(kAxisRaw[axis], f.raw_bytes[axis], f.raw[axis]);
  }
}

// One axis's residuals in coding order (the sections of that axis). The
// residual coder is inlined into this loop, bfs3d's decoding time: GCC
// does so by itself, clang (and so WebAssembly) only when told.
template <class EntropyIO>
[[gnu::flatten]] void describe_axis(EntropyIO& io, std::span<int32_t> residuals) {
  ResidualCoder<1> model;
  for (int32_t& r : residuals) model.describe(io, 0, r, kMotionResidual);
}

}  // namespace syntax

}  // namespace m4mesh
