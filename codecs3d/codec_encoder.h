// The encoding half of a 3D codec, unit by unit, mirroring
// codecs3d/codec_decoder.h: the codec reads the frames it needs from a
// FrameSource (mesh3d/frame_source.h) and emits its units through a UnitSink, which the container encoder
// (encoder/mesh3d/container_encoder.h) implements: it writes the unit headers, the hash
// units of the frames the codec reports decoded, and the trace.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/point3.h"
#include "mesh3d/frame_source.h"
#include "syntax/io.h"
#include "syntax/mesh3d/container.h"

namespace m4mesh {

class UnitSink {
 public:
  virtual ~UnitSink() = default;
  // Writes a unit: its header, then its data through `write`, whose io
  // counts offsets from the payload's start and traces in the unit's place.
  virtual void unit(UnitType type, uint32_t frame, const std::function<void(syntax::WriteIO&)>& write) = 0;
  // The decoder's state of a frame after the last unit (the closed loop):
  // hashed when the stream carries hash units.
  virtual void decoded(uint32_t frame, std::span<const Float3> positions) = 0;
  // The frames reported so far are final (a progressive codec's segment
  // ends): hash units cover them now, a group hash the ones still waiting
  // for the rest of their group; later groups count from the next frame.
  virtual void end_segment() = 0;
  virtual void progress(size_t done, size_t total) = 0;
  // The stream's bytes so far: start codes, escaping and hash units included.
  virtual uint64_t stream_bytes() const = 0;
};

// A codec's own figure for the summary ("matrices", 1234).
using CodecStatistic = std::pair<std::string, double>;

class CodecEncoder3d {
 public:
  virtual ~CodecEncoder3d() = default;
  // The codec header after the object header.
  virtual void write_header(syntax::WriteIO& io) = 0;
  // Emits every unit of the sequence.
  virtual void encode(const FrameSource& frames, UnitSink& sink) = 0;
  virtual std::vector<CodecStatistic> statistics() const { return {}; }
};

// How the encoder codes base meshes beyond their content: the positions'
// blend (docs/base_mesh.md), or without one the one of 0 … 16 that codes
// each base mesh in the fewest bytes; and whether the vertices are numbered
// in coding order (--reorder: vertex_order 0), else the input's numbers
// are sent, also when the traversal numbers the vertices as the input does,
// so that a decoder's vertex_order tells whether the input's numbers hold.
struct BaseMeshCoding {
  std::optional<uint32_t> position_blend;
  bool coding_order = false;
};

// A base mesh unit's data (docs/base_mesh.md): the faces, which must be in
// coding order (the container encoder puts them so), and the grid
// positions; `untraversed` as for plan_base_mesh (encoder/mesh3d/base_mesh.h).
// Returns the position_blend written.
uint32_t write_base_mesh(syntax::WriteIO& io, std::span<const Triangle> faces, std::span<const IntPoint3> positions,
                         const BaseMeshCoding& coding, std::span<const uint32_t> untraversed = {});

// The bytes of a base mesh's parts as write_base_mesh codes them, each
// alone in its own sections with fresh contexts (a figure, not a stream).
struct BaseMeshParts {
  size_t connectivity = 0;  // the traversal and the loose faces
  size_t vertex_order = 0;  // 0 in coding order
  size_t positions = 0;
};
BaseMeshParts base_mesh_parts(std::span<const Triangle> faces, std::span<const IntPoint3> positions, const BaseMeshCoding& coding);

}  // namespace m4mesh
