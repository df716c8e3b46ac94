// `m4mesh demo`: the main job on an embedded input.
#pragma once

#include <cstdint>
#include <string>

#include "mesh/plane.h"

namespace m4mesh {

struct DemoOptions {
  uint32_t cols = 33;
  uint32_t rows = 25;
  uint32_t spacing = 16;  // half pixels
  uint32_t frames = 120;
  std::string gif;  // the decoded animation drawn on a checkerboard (empty: none)
};

// Plane t of a flag waving on a pole: a uniform I-plane (t = 0), then P-planes.
MeshPlane waving_flag_plane(const DemoOptions& options, uint32_t t);

// Encodes, decodes, checks bit-exactness and prints figures; returns the
// exit status. One plane at a time: memory does not grow with the frames.
int run_demo(const DemoOptions& options);

}  // namespace m4mesh
