// Draco as the reference the benchmarks measure m4mesh against; nothing
// of Draco's is in a stream m4mesh writes or reads.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"

namespace m4mesh {

// Draco coding one frame at `bits` quantization with edgebreaker, as the
// reference rate of "Draco coding every frame".
size_t draco_frame_size(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits);
// The positions Draco's decoder gives back for that frame, in the input's
// vertex order (coded sequentially, which keeps the order and quantizes
// as edgebreaker does).
std::vector<std::array<float, 3>> draco_frame_decoded(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits);

// One frame as Draco codes it with edgebreaker at `bits` quantization, and
// the number of points Draco's decoder gives back from such bytes (the
// speed anchor of the scale benchmark).
std::vector<char> draco_frame_encoded(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits);
size_t draco_frame_decode(std::span<const char> encoded);

// Draco coding grid positions losslessly with edgebreaker (which reorders
// vertices) or with sequential coding (which keeps their order).
size_t draco_grid_size(std::span<const Triangle> faces, std::span<const IntPoint3> positions, bool edgebreaker);

}  // namespace m4mesh
