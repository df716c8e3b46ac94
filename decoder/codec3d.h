// The decoding half of each 3D codec: it reads its codec header, learns the
// base mesh, and turns frame units into grid positions. The container
// decoder (mesh3d_decoder.h) does the rest.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "mesh/topology.h"
#include "mesh3d/quantization.h"
#include "syntax/io.h"

namespace m4mesh {

class CodecDecoder3d {
 public:
  virtual ~CodecDecoder3d() = default;

  // The grid of the base mesh's integer positions.
  virtual const Grid& grid() const = 0;
  // Called after every base mesh unit (frame 0 and intra refreshes).
  virtual void start(std::span<const Triangle> faces, uint32_t vertex_count) = 0;
  // Decodes a frame unit's data (after the unit header) from the previous
  // frame's positions into the new ones. Errors name the element; the
  // container decoder adds the frame and the unit's offset.
  virtual void decode_frame(std::span<const uint8_t> data, std::vector<IntPoint3>& positions) = 0;
};

// Reads the codec header that follows the object header.
std::unique_ptr<CodecDecoder3d> read_bfs3d_header(syntax::ReadIO& io);
std::unique_ptr<CodecDecoder3d> read_affine_octree_header(syntax::ReadIO& io);

// An error of a frame's data, located by the caller.
[[noreturn]] void frame_data_error(ErrorKind kind, const char* element, const std::string& message);

}  // namespace m4mesh
