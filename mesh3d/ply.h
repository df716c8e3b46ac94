// PLY frames (the Stanford polygon format): written binary little-endian
// (x, y, z as float, faces as a uchar count and int indices); read in ASCII
// or binary little-endian with any scalar types, x, y and z from the
// "vertex" element and polygons (fanned into triangles) from the "face"
// element's vertex_indices list; other elements and properties are skipped.
#pragma once

#include <span>
#include <string>

#include "mesh3d/sequence.h"

namespace m4mesh {

MeshFrame read_ply(const std::string& path);
void write_ply_frame(std::span<const Vec3> positions, std::span<const Triangle> faces, const std::string& path);

}  // namespace m4mesh
