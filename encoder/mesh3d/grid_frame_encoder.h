// The encoding of codecs that code one frame per unit against the previous
// decoded frame on an integer grid (bfs3d, Affine-Octree), mirroring
// decoder/mesh3d/grid_frame_decoder.h: a base mesh for frame 0 and every
// intra frame, a frame unit for the others. A codec implements
// encode_frame() and nothing else of the units.
#pragma once

#include <vector>

#include "codecs3d/codec_encoder.h"
#include "mesh3d/quantization.h"

namespace m4mesh {

class GridFrameEncoder : public CodecEncoder3d {
 public:
  GridFrameEncoder(const Grid& grid, int intra_period, const BaseMeshCoding& base_mesh)
      : grid_(grid), intra_period_(intra_period), base_mesh_(base_mesh) {}

  void encode(const FrameSource& frames, UnitSink& sink) final;

 protected:
  // Writes a frame unit's data for `frame` (original positions) against
  // the decoded previous frame, which it replaces by the decoded new one.
  virtual void encode_frame(syntax::WriteIO& io, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions) = 0;

  const Grid grid_;

 private:
  int intra_period_;
  BaseMeshCoding base_mesh_;
};

// A frame on the grid; an input error names the frame and vertex that do not fit.
void quantize_frame(const Grid& grid, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions);

}  // namespace m4mesh
