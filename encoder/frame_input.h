// Encoder input from mesh frame sequences (OBJ): x and y of every vertex,
// scaled to half pixels and rounded. The first frame becomes a uniform
// I-plane when it is exactly a §5 grid, otherwise a Delaunay I-plane with
// the mesh's boundary loop as its boundary; later frames are P-planes.
#pragma once

#include <string>
#include <vector>

#include "mesh/obj.h"
#include "mesh/plane.h"

namespace m4mesh {

struct FrameInput {
  std::vector<MeshPlane> planes;
  // input_vertex[i]: the frame vertex that plane node i holds.
  std::vector<NodeIndex> input_vertex;
};

FrameInput planes_from_frames(const std::vector<ObjFrame>& frames, const std::vector<std::string>& names, double scale);

// The §5 parameters of nodes and triangles that form a uniform mesh exactly.
bool detect_uniform(const std::vector<Point>& nodes, const std::vector<Triangle>& triangles, UniformParams& params);

}  // namespace m4mesh
