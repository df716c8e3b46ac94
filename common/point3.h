// Fixed-size points shared by every layer of the 3D side.
#pragma once

#include <array>
#include <cstdint>

namespace m4mesh {

using IntPoint3 = std::array<int32_t, 3>;  // a position on a quantization grid
using Float3 = std::array<float, 3>;       // a decoded position (binary32)
// Positions are copied out as arrays of x, y, z floats.
static_assert(sizeof(Float3) == 3 * sizeof(float));

}  // namespace m4mesh
