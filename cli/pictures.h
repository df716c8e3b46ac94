// `m4mesh render`: a decoded 2D mesh animation as pictures, the texture
// warped by each plane (render/texture_warp.h), to an animated GIF or one
// plane's PNG.
#pragma once

#include <cstdint>
#include <string>

namespace m4mesh {

struct RenderArgs {
  std::string input;
  std::string output;   // .gif (every plane) or .png (one plane)
  std::string texture;  // a PNG; empty: a checkerboard
  uint32_t plane = 0;   // the plane of a .png
  bool wireframe = false;
  double fps = 25;
};
int run_render(const RenderArgs& args);

}  // namespace m4mesh
