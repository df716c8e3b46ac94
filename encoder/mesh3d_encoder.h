// Encoders of 3D dynamic meshes into the §12 container.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "mesh3d/sequence.h"
#include "syntax/container.h"

namespace m4mesh {

struct Encode3dOptions {
  uint32_t codec_id = kCodecBfs3d;
  int bits = 12;               // quantization bits per coordinate
  bool parallelogram = false;  // bfs3d: parallelogram instead of average prediction
  bool hashes = true;          // a decoded-frame hash unit after every frame
  uint32_t frame_rate_num = 25;
  uint32_t frame_rate_den = 1;
  std::function<void(size_t done, size_t total)> progress;
};

struct Encode3dResult {
  std::vector<uint8_t> stream;
  uint64_t base_bytes = 0;   // the base mesh unit, start code included
  uint64_t frame_bytes = 0;  // every frame unit, start codes included
  uint64_t other_bytes = 0;  // object header, hash units, end code
};

Encode3dResult encode_mesh3d(const MeshSequence& sequence, const Encode3dOptions& options = {});

}  // namespace m4mesh
