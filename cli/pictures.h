// `m4mesh render`: a decoded 2D mesh animation as pictures, the texture
// warped by each plane (render/texture_warp.h), to an animated GIF or one
// plane's PNG. `m4mesh render3d`: shaded views of a 3D sequence or stream
// (render/shaded.h), beside its original with the error as colours.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "render/shaded.h"

namespace m4mesh {

struct RenderArgs {
  std::string input;
  std::string output;   // .gif (every plane) or .png (one plane)
  std::string texture;  // a PNG; empty: a checkerboard
  uint32_t plane = 0;   // the plane of a .png
  bool wireframe = false;
  std::optional<double> fps;  // default: the texture's frame rate (a texture from track), else 25
  uint32_t size = 0;    // the picture's longer side in pixels (0: one pixel per half pixel of the mesh)
};
int run_render(const RenderArgs& args);

struct Render3dArgs {
  std::string input;    // a sequence or a mesh3d stream
  std::string output;   // .png (one frame) or .gif (every frame)
  std::string compare;  // the original: drawn beside, the input coloured by its error
  uint32_t frame = 0;   // the frame of a .png
  uint32_t size = 512;  // pixels per view
  double azimuth = 30, elevation = 20;  // degrees
  double fps = 25;
  View view = View::kFollow;          // what each frame's view frames
  std::optional<double> max_error;    // the top of the colour scale (default: the largest error)
};
int run_render3d(const Render3dArgs& args);

}  // namespace m4mesh
