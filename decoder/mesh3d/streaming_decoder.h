// A 3D stream decoded as its bytes arrive, for the C interface and the npm
// package: push() the bytes as they come, finish() once they are all
// there. Units are decoded as soon as they are whole, frames then wait in
// the Mesh3dDecoder for next_frame(); only the bytes of the units not
// decoded yet are kept.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "decoder/mesh3d/container_decoder.h"

namespace m4mesh {

class StreamingMesh3dDecoder {
 public:
  // Appends `bytes` and decodes the units they complete; returns how many
  // units that decoded, hash units aside. Its cost is in proportion to the
  // bytes pushed and the units decoded, whatever the size of the pieces;
  // bytes that cannot start a 3D stream fail at once. A frame that fails
  // its hash unit is an error (structure, element frame_md5 or group_md5).
  size_t push(std::span<const uint8_t> bytes);
  // The stream's end: decodes the units left.
  size_t finish();
  bool finished() const { return ended_; }

  // Null until the object header and codec header have arrived.
  Mesh3dDecoder* decoder() { return decoder_.get(); }
  const Mesh3dDecoder* decoder() const { return decoder_.get(); }
  uint64_t bytes_received() const { return received_start_ + received_.size(); }
  // The bytes up to the end of the last unit decoded.
  uint64_t bytes_decoded() const { return bytes_decoded_; }

 private:
  // Decodes the units whole in the first `size` bytes held.
  size_t take(size_t size);

  std::vector<uint8_t> received_;  // the stream's bytes from received_start_ on
  uint64_t received_start_ = 0;
  uint64_t bytes_decoded_ = 0;
  uint64_t scanned_ = 0;          // a start code cannot begin before this but at last_start_code_
  uint64_t last_start_code_ = 0;  // the last start code's offset (0: none after the object's)
  std::unique_ptr<Mesh3dDecoder> decoder_;
  bool ended_ = false;
};

}  // namespace m4mesh
