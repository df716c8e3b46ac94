// The decoder of §12 containers: one frame at a time, each checked against
// its decoded-frame hash unit when the stream carries one.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "decoder/codec3d.h"
#include "mesh3d/quantization.h"
#include "syntax/container.h"

namespace m4mesh {

class Mesh3dDecoder {
 public:
  // The stream is not copied: it must outlive the decoder. With `verify`,
  // each frame is checked against its hash unit (hash_matches()).
  explicit Mesh3dDecoder(std::span<const uint8_t> stream, bool verify = false);
  Mesh3dDecoder(std::vector<uint8_t>&&, bool = false) = delete;

  const ObjectHeader& header() const { return header_; }
  const std::vector<Triangle>& faces() const { return faces_; }
  // The grid of the codec's integer positions.
  const Grid& codec_grid() const { return codec_->grid(); }

  // Decodes the next frame; false after the last.
  bool next_frame();
  uint32_t frame_index() const { return frame_index_; }
  const std::vector<Float3>& positions() const { return positions_; }
  // The frame's hash unit: nothing when the stream has none for it (or
  // verification is off), else whether the decoded frame matches it.
  std::optional<bool> hash_matches() const { return hash_matches_; }
  bool has_end_code() const { return parts_.has_end_code; }

 private:
  void decode_base(const ContainerUnit& unit, uint32_t frame);
  void decode_frame(const ContainerUnit& unit, uint32_t frame);
  void check_hash();
  [[noreturn]] void fail(ErrorKind kind, const ContainerUnit& unit, uint32_t frame, const char* element, const std::string& message) const;

  ContainerParts parts_;
  size_t next_unit_ = 0;
  ObjectHeader header_;
  std::unique_ptr<CodecDecoder3d> codec_;
  std::vector<Triangle> faces_;
  std::vector<IntPoint3> quantized_;
  std::vector<Float3> positions_;
  uint32_t frame_index_ = 0;
  bool started_ = false;
  bool verify_;
  std::optional<bool> hash_matches_;
};

// The whole sequence (tests, tools); fails on a hash mismatch.
MeshSequence decode_mesh3d(std::span<const uint8_t> stream);

}  // namespace m4mesh
