#include "decoder/mesh3d/grid_frame_decoder.h"

namespace m4mesh {

void GridFrameDecoder::decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) {
  // The unit is the next frame even when it fails, so that a check carries on.
  const uint32_t expected = started_ ? frame_index_ + 1 : first_frame_;
  const bool first = !started_;
  started_ = true;
  frame_index_ = expected;
  decoded.push_back(expected);
  if (unit.frame_index != expected) {
    io.set_plane(expected);
    io.fail(ErrorKind::kStructure, "frame_index",
            "frame " + std::to_string(unit.frame_index) + " where frame " + std::to_string(expected) + " was expected");
  }
  if (unit.type() == UnitType::kBaseMesh) {
    BaseMesh base = read_base_mesh(io, object_, trace_);
    if (first) {
      faces_ = std::move(base.faces);
      start(faces_, object_.vertex_count);
    } else if (base.faces != faces_) {
      io.fail(ErrorKind::kStructure, "base_mesh", "an intra base mesh with other faces than frame 0's");
    }
    positions_ = std::move(base.positions);
  } else {
    decode_frame(io, positions_);
  }
}

bool GridFrameDecoder::start_at(uint32_t frame) {
  if (started_) return false;
  first_frame_ = frame;
  return true;
}

void GridFrameDecoder::frame(uint32_t, std::span<Float3> positions) const {
  const Grid grid = grid_;  // a copy, which the stores below cannot alias
  for (size_t i = 0; i < positions_.size(); ++i)
    for (int axis = 0; axis < 3; ++axis) positions[i][axis] = grid.position(axis, positions_[i][axis]);
}

}  // namespace m4mesh
