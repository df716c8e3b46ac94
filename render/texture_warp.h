// A decoded 2D mesh animation as pictures (claim 19 of the mesh object's
// source, ../shared/seeds/003_…): the texture lies on the I-plane's
// triangles, and each later plane warps it triangle by triangle, by the
// affine map between the triangle's I-plane and current positions,
// sampling the texture bilinearly. Mesh coordinates are half pixels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/geometry.h"
#include "mesh/topology.h"
#include "render/image.h"

namespace m4mesh {

// A pixel rectangle: the picture's columns x0 … x0 + width − 1.
struct Canvas {
  int64_t x0 = 0, y0 = 0;
  uint32_t width = 0, height = 0;
};
// The pixels the nodes reach, and the rectangle holding two of them.
Canvas canvas_over(std::span<const Point> nodes);
Canvas united(const Canvas& a, const Canvas& b);

// A checkerboard of `square`-pixel squares, for a mesh without a texture.
Image checkerboard(uint32_t width, uint32_t height, uint32_t square = 16);

class TextureWarp {
 public:
  // The texture is stretched over the pixels of the I-plane's nodes.
  TextureWarp(std::span<const Point> intra_nodes, std::span<const Triangle> triangles, const Image& texture, const Canvas& canvas);
  // The texture is stretched over `texture_box`.
  TextureWarp(std::span<const Point> intra_nodes, std::span<const Triangle> triangles, const Image& texture, const Canvas& texture_box,
              const Canvas& canvas);

  // The plane whose nodes are `nodes` (the I-plane's indices); pixels no
  // triangle covers are the background (0 in `covered`, when given); with
  // `wireframe`, edges drawn over.
  Image render(std::span<const Point> nodes, bool wireframe, std::vector<uint8_t>* covered = nullptr) const;

 private:
  struct Texel {
    double u, v;
  };

  std::vector<Triangle> triangles_;
  std::vector<Texel> texels_;  // per node: where its I-plane position lies in the texture
  const Image& texture_;
  Canvas canvas_;
};

}  // namespace m4mesh
