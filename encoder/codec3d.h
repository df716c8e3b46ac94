// The encoding half of each 3D codec; the container encoder
// (mesh3d_encoder.h) writes the object, base meshes, hashes and units.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "encoder/mesh3d_encoder.h"
#include "mesh3d/quantization.h"
#include "syntax/io.h"

namespace m4mesh {

class CodecEncoder3d {
 public:
  virtual ~CodecEncoder3d() = default;

  // The grid of the base mesh's integer positions.
  virtual const Grid& grid() const = 0;
  virtual void write_header(syntax::WriteIO& io) = 0;
  // Codes a frame (original positions) against the decoded previous frame,
  // which it replaces by the decoded new one: the closed loop.
  virtual std::vector<uint8_t> encode_frame(std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions,
                                            Encode3dResult& statistics) = 0;
};

std::unique_ptr<CodecEncoder3d> make_bfs3d_encoder(const MeshSequence& sequence, const Encode3dOptions& options);
std::unique_ptr<CodecEncoder3d> make_affine_octree_encoder(const MeshSequence& sequence, const Encode3dOptions& options);

// A frame on the grid; an input error names the frame and vertex that do not fit.
void quantize_frame(const Grid& grid, std::span<const Vec3> frame, size_t frame_index, std::vector<IntPoint3>& positions);

}  // namespace m4mesh
