// The per-axis quantization grid of a 3D codec header: origin and step of
// every axis as binary32 bit patterns, described once for every codec.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "common/bit_cast.h"
#include "syntax/io.h"

namespace m4mesh::syntax {

// origin_x, step_x, origin_y, step_y, origin_z, step_z: finite, steps > 0.
template <class IO>
void describe_grid(IO& io, std::array<uint32_t, 3>& origin, std::array<uint32_t, 3>& step) {
  static const char* const kOrigin[3] = {"origin_x", "origin_y", "origin_z"};
  static const char* const kStep[3] = {"step_x", "step_y", "step_z"};
  for (int axis = 0; axis < 3; ++axis) {
    binary32(io, kOrigin[axis], origin[axis]);
    io.require(std::isfinite(bit_cast<float>(origin[axis])), ErrorKind::kOutOfRange, kOrigin[axis], "not a finite binary32");
    binary32(io, kStep[axis], step[axis]);
    const float s = bit_cast<float>(step[axis]);
    io.require(std::isfinite(s) && s > 0, ErrorKind::kOutOfRange, kStep[axis], "not a positive finite binary32");
  }
}

}  // namespace m4mesh::syntax
