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

void GridFrameEncoder::encode(const FrameSource& frames, UnitSink& sink) {
  std::vector<IntPoint3> positions;
  std::vector<Float3> decoded;
  FrameReader reader(frames);
  for (uint32_t f = 0; f < frames.frame_count(); ++f) {
    const std::span<const Vec3> frame = reader.get(f);
    if (f == 0 || (intra_period_ > 0 && f % static_cast<uint32_t>(intra_period_) == 0)) {
      quantize_frame(grid_, frame, f, positions);
      sink.unit(UnitType::kBaseMesh, f, [&](syntax::WriteIO& io) { write_base_mesh(io, frames.faces(), positions, base_mesh_); });
    } else {
      sink.unit(UnitType::kFrame, f, [&](syntax::WriteIO& io) { encode_frame(io, frame, f, positions); });
    }
    decoded.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
      for (int axis = 0; axis < 3; ++axis) decoded[i][axis] = grid_.position(axis, positions[i][axis]);
    sink.decoded(f, decoded);
    sink.progress(f + size_t{1}, frames.frame_count());
  }
}

}  // namespace m4mesh
