// Animated triangle meshes with fixed connectivity, and their files: OBJ
// or OFF frame sequences (a folder or a pattern, numeric frame order) and
// the project's compact binary format (.m4seq).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "mesh/topology.h"

namespace m4mesh {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  friend bool operator==(const Vec3&, const Vec3&) = default;
};

// The axis-aligned bounding box of points; empty (lo > hi) before the first.
struct Box3 {
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(std::span<const Vec3> points) {
    for (const Vec3& p : points) add(p);
  }
};

inline Box3 box_of(std::span<const Vec3> points) {
  Box3 box;
  box.add(points);
  return box;
}

struct MeshSequence {
  uint32_t vertex_count = 0;
  std::vector<Triangle> faces;
  std::vector<std::vector<Vec3>> frames;
};

// A folder of frames (.obj, .off or .ply: frame_files), a pattern with
// '*', a single frame file, a .m4seq file ("-": one on standard input), or
// a .pc2 file with its faces in the .obj beside it. Every frame must have
// the first frame's vertex count and faces; the error names the first
// frame that differs.
MeshSequence load_sequence(const std::string& path, bool report_progress = false);

// .m4seq: "M4SEQ1\n", vertex_count u32, face_count u32, frame_count u32,
// faces (3 × u32 each), then every frame's positions as binary32 (x y z per
// vertex); all little-endian.
void write_binary_sequence(const MeshSequence& sequence, const std::string& path);
MeshSequence read_binary_sequence(const std::string& path);

// PC2 (Point Cache 2, the vertex cache of Blender, 3ds Max and Maya):
// "POINTCACHE2\0", int32 version 1, int32 point count, float32 start frame,
// float32 sample rate, int32 sample count, then samples × points × 3
// float32, little-endian; one frame per sample. The faces come from the OBJ
// of the same name beside it (flag.pc2 → flag.obj), with as many vertices.
MeshSequence read_pc2_sequence(const std::string& path);
// Writes both: the OBJ first (frame 0 and the faces), then the PC2.
void write_pc2_sequence(const MeshSequence& sequence, const std::string& path);
// The OBJ beside a PC2 file.
std::string pc2_faces_path(const std::string& path);

// Frames as OBJ files 0001.obj, 0002.obj, … in a folder (created if needed).
void write_obj_frames(const MeshSequence& sequence, const std::string& folder);
void write_obj_frame(std::span<const Vec3> positions, std::span<const Triangle> faces, const std::string& path);
// "0001.obj" for frame index 0.
std::string obj_frame_name(size_t frame_index);

// One OFF frame: "OFF", counts, vertices, polygons (fanned into triangles).
struct MeshFrame {
  std::vector<Vec3> vertices;
  std::vector<Triangle> faces;
  std::vector<std::string> dropped;  // what the file held besides positions and faces (OBJ: vt, vn, usemtl, …)
};
MeshFrame read_off(const std::string& path);

}  // namespace m4mesh
