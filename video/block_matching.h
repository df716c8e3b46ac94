// Block-matching motion compensation, the anchor the mesh-motion papers
// compare against: each block of the current frame takes the block of the
// previous frame that matches its luma best (full search of whole-pixel
// offsets within ±range, then the eight half-pixel neighbours of the best).
#pragma once

#include <cstdint>

#include "render/image.h"
#include "video/tracking/luma.h"

namespace m4mesh {

struct BlockPrediction {
  Image picture;      // the current frame as the previous frame's blocks predict it
  uint32_t blocks = 0;  // motion vectors
};

BlockPrediction block_prediction(const Image& previous, const Luma& previous_luma, const Luma& current_luma, uint32_t block, uint32_t range);

// The luma (BT.601 weights) of a picture.
Luma luma_of(const Image& picture);

}  // namespace m4mesh
