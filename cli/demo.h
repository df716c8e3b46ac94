// `m4mesh demo`: the main job on an embedded input.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/plane.h"

namespace m4mesh {

struct DemoOptions {
  uint32_t cols = 33;
  uint32_t rows = 25;
  uint32_t spacing = 16;  // half pixels
  uint32_t frames = 120;
};

// A flag waving on a pole: a uniform I-plane then P-planes.
std::vector<MeshPlane> waving_flag(const DemoOptions& options);

// Encodes, decodes, checks bit-exactness and prints figures; returns the exit status.
int run_demo(const DemoOptions& options);

}  // namespace m4mesh
