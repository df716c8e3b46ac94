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
  double max_error = 0.01;     // affine-octree: ME, the largest vertex error of an affine cell, over the root cube's side
  int matrix_bits = 16;        // affine-octree: k, bits per matrix element
  int matrix_range_log2 = 2;   // affine-octree: elements in [−2^(r−1), 2^(r−1))
  int max_depth = 16;          // affine-octree: the deepest octree level
  int intra_period = 0;        // a base mesh unit (intra frame) every N frames; 0: frame 0 only
  bool hashes = true;          // a decoded-frame hash unit after every frame
  uint32_t frame_rate_num = 25;
  uint32_t frame_rate_den = 1;
  std::function<void(size_t done, size_t total)> progress;
};

struct Encode3dResult {
  std::vector<uint8_t> stream;
  uint64_t base_bytes = 0;   // the base mesh units, start codes included
  uint64_t frame_bytes = 0;  // every frame unit, start codes included
  uint64_t matrices = 0;     // affine-octree: affine leaves in all frames
  uint64_t direct_vertices = 0;  // affine-octree: vertices coded by direct motion
  uint64_t other_bytes = 0;  // object header, hash units, end code
};

Encode3dResult encode_mesh3d(const MeshSequence& sequence, const Encode3dOptions& options = {});

}  // namespace m4mesh
