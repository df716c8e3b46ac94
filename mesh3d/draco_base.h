// The base mesh of a 3D stream (unit_type 0): connectivity and the first
// frame's quantized integer positions, coded with Draco's sequential mesh
// encoding, which keeps the order of vertices and faces. Draco codes the
// integers losslessly, so no floating point of Draco's is in the decoding path.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/point3.h"
#include "mesh/topology.h"

namespace m4mesh {

std::vector<uint8_t> encode_base_mesh(std::span<const Triangle> faces, std::span<const IntPoint3> positions);

struct BaseMesh {
  std::vector<Triangle> faces;
  std::vector<IntPoint3> positions;
};

// Checks the counts against the object header and every face index (kInput
// errors are turned into located errors by the caller).
BaseMesh decode_base_mesh(std::span<const uint8_t> data, uint32_t vertex_count, uint32_t face_count);

// Draco on its own: one frame at `bits` quantization with edgebreaker, as
// the reference rate of "Draco coding every frame".
size_t draco_frame_size(std::span<const Triangle> faces, std::span<const std::array<float, 3>> positions, int bits);

}  // namespace m4mesh
