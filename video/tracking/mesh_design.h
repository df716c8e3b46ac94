// Meshes laid on a video's first frame, in half pixels, with how each node
// may move while it is tracked (node_tracker.h). A frame's mesh spans
// half pixels 0 … 2W − 1 across (the first pixel's left edge to the last
// pixel's centre): render/texture_warp.h then lays a W-pixel texture over
// it one texel to a pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/plane.h"
#include "video/tracking/luma.h"
#include "video/tracking/node_tracker.h"

namespace m4mesh {

struct FrameMesh {
  MeshPlane plane;        // the I-plane; its node i is node i of `tracking`
  TrackingMesh tracking;  // the same nodes and the decoder's triangles (§9 order, as it draws them)
};

// The largest frame side a mesh covers: coordinates reach 1023 half pixels.
inline constexpr uint32_t kMaxMeshFrameSide = 512;

// A uniform mesh of cell_width × cell_height-pixel rectangles (split code
// 0). Where the cells do not divide the frame, the last column and row of
// nodes lie less than one cell past it. Corners stay; the other border
// nodes slide along their edge. A frame smaller than one cell is a kUsage error.
FrameMesh uniform_frame_mesh(uint32_t width, uint32_t height, uint32_t cell_width, uint32_t cell_height);

// Pixels that belong to an object (non-zero), row by row.
struct Mask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> inside;
};

// The object a mask outlines: its largest 8-connected part after a 3 × 3
// opening, holes filled. A kInput error when nothing is left.
Mask mask_object(const Mask& mask);

// A content-based Delaunay mesh of about `nodes` nodes (spacing
// d = √(area / nodes)). Boundary: the frame's rectangle, its edges cut
// every d (corners stay, edge nodes slide), or with a mask the object's
// outline sampled every d pixels (nodes move freely). Interior: three
// quarters of the nodes where the picture has structure (the smaller
// eigenvalue of the 5 × 5 structure tensor, Shi & Tomasi), at
// least 0.7 d apart, the rest where the mesh is emptiest (farthest point),
// all at pixel centres at least d / 3 inside the boundary. Nodes are in the
// §10 coded order, so the stream's node i is node i here.
FrameMesh content_frame_mesh(const Luma& frame, uint32_t nodes, const Mask* mask);

}  // namespace m4mesh
