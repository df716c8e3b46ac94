// The decoding of codecs that code one frame per unit, in display order,
// against the previous decoded frame on an integer grid (bfs3d,
// Affine-Octree): base mesh units (frame 0 and intra refreshes) and frame
// units. A codec implements decode_frame() and nothing else of the units.
#pragma once

#include <vector>

#include "codecs3d/codec_decoder.h"
#include "mesh3d/quantization.h"

namespace m4mesh {

class GridFrameDecoder : public CodecDecoder3d {
 public:
  GridFrameDecoder(const ObjectHeader& object, const Grid& grid) : object_(object), grid_(grid) {}

  void decode_unit(const UnitHeader& unit, syntax::ReadIO& io, std::vector<uint32_t>& decoded) final;
  const std::vector<Triangle>& faces() const final { return faces_; }
  void frame(uint32_t index, std::span<Float3> positions) const final;
  bool start_at(uint32_t frame) final;

 protected:
  // Called once the base mesh of frame 0 is known.
  virtual void start(std::span<const Triangle> faces, uint32_t vertex_count) = 0;
  // Decodes a frame unit's data from the previous frame's positions into
  // the new ones.
  virtual void decode_frame(syntax::ReadIO& io, std::vector<IntPoint3>& positions) = 0;

  const ObjectHeader object_;

 private:
  const Grid grid_;
  std::vector<Triangle> faces_;
  std::vector<IntPoint3> positions_;
  bool started_ = false;
  uint32_t first_frame_ = 0;  // of the first unit: 0, or an intra refresh
  uint32_t frame_index_ = 0;
};

}  // namespace m4mesh
