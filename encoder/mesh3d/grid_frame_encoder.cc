#include "encoder/mesh3d/grid_frame_encoder.h"

#include "common/error.h"

namespace m4mesh {

void quantize_frame(const Grid& grid, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) {
  positions.resize(frame.size());
  for (size_t i = 0; i < frame.size(); ++i)
    if (!grid.quantize(frame[i], positions[i]))
      throw Error(ErrorKind::kInput, "", kNoPlane, kNoOffset,
                  "frame " + std::to_string(frame_index) + ", vertex " + std::to_string(i) +
                      " lies beyond the quantization grid's ±2^26 steps");
}

void GridFrameEncoder::encode(const MeshSequence& s, UnitSink& sink) {
  std::vector<IntPoint3> positions;
  std::vector<Float3> decoded;
  for (size_t f = 0; f < s.frames.size(); ++f) {
    const uint32_t frame = static_cast<uint32_t>(f);
    if (f == 0 || (intra_period_ > 0 && f % static_cast<size_t>(intra_period_) == 0)) {
      quantize_frame(grid_, s.frames[f], f, positions);
      sink.unit(UnitType::kBaseMesh, frame, [&](syntax::WriteIO& io) { write_base_mesh(io, s.faces, positions, base_mesh_); });
    } else {
      sink.unit(UnitType::kFrame, frame, [&](syntax::WriteIO& io) { encode_frame(io, s.frames[f], f, positions); });
    }
    decoded.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
      for (int axis = 0; axis < 3; ++axis) decoded[i][axis] = grid_.position(axis, positions[i][axis]);
    sink.decoded(frame, decoded);
    sink.progress(f + 1, s.frames.size());
  }
}

}  // namespace m4mesh
