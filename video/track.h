// A video turned into a 2D mesh object (the encoder's front end): a mesh
// laid on the first frame, its nodes tracked through the video
// (video/tracking/), the planes coded by the 2D encoder, with the
// measurements of the mesh-motion literature beside them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/image.h"
#include "video/tracking/mesh_design.h"
#include "video/tracking/node_tracker.h"
#include "video/video_reader.h"

namespace m4mesh {

struct TrackSettings {
  uint32_t cell_width = 16, cell_height = 16;  // a uniform mesh's cells, pixels (when nodes == 0)
  uint32_t nodes = 0;                          // > 0: a content-based Delaunay mesh of about this many nodes
  const Image* mask = nullptr;                 // the object in the first frame (non-black); Delaunay meshes only
  int64_t first_frame = 0;
  int64_t end_frame = -1;  // the first frame not tracked; −1: the video's end
  TrackerOptions tracker;
  // A new I-plane, the mesh laid out again on the frame, when the tracked
  // mesh degrades: more than kMostStrained of its triangles have grown or
  // shrunk past this factor of their area in the I-plane (content occluded
  // or revealed, such as people walking past; the tracker stops them at
  // kMaxStretch), or it covers less than kLeastCoverage of the frame (a
  // pan). 0: never (and never with a mask: the object's outline is known
  // on the first frame only).
  double remesh_stretch = 3;
  uint32_t block = 0;  // block matching's block side; 0: the side giving as many blocks as nodes
  std::function<void(int64_t done, int64_t total)> progress;  // total 0: not known
};

// Luma PSNRs (dB) over the pixels the mesh covers in that frame.
struct TrackedFrame {
  int64_t frame = 0;       // in the video
  uint64_t bits = 0;       // its plane in the stream
  double coverage = 0;     // share of the frame's pixels the mesh covers
  double render_psnr = 0;  // the texture warped by this plane (what `m4mesh render` draws) against the frame
  double mesh_psnr = 0;    // the previous frame warped by the mesh's motion to this frame (NaN at an I-plane)
  double block_psnr = 0;   // block matching with as many vectors (NaN at an I-plane)
  bool intra = false;      // an I-plane: a mesh laid out on this frame
  double stretch = 1;      // the largest growth or shrinking of a triangle's area since its I-plane (≥ 1)
  double strained = 0;     // the share of triangles grown or shrunk past TrackSettings::remesh_stretch
};

// A later I-plane: a mesh laid out again on the frame of plane `plane`, with that frame as its texture.
struct Remesh {
  size_t plane = 0;
  FrameMesh mesh;
  Image texture;
};

// When a new I-plane is due (TrackSettings::remesh_stretch), at the
// earliest kFewestPlanesPerMesh planes after the last: a mesh that
// degrades sooner shows tracking that a new mesh does not mend (the
// content's flat regions give its nodes nothing to hold on to).
inline constexpr double kLeastCoverage = 0.8;
inline constexpr double kMostStrained = 0.02;
inline constexpr size_t kFewestPlanesPerMesh = 8;

struct TrackResult {
  VideoInfo video;
  FrameMesh mesh;
  std::vector<std::vector<Point>> positions;  // per frame, by node of the mesh in force, half pixels
  Image texture;                              // the first frame over the mesh's rectangle
  std::vector<Remesh> remeshes;               // later I-planes, in plane order
  std::vector<uint8_t> stream;
  std::vector<TrackedFrame> frames;
  uint32_t block = 0, blocks = 0;  // block matching's side and its vectors a frame
  int levels = 0;                  // the tracker's pyramid levels
  std::vector<std::string> warnings;
};

TrackResult track_video(const std::string& path, const TrackSettings& settings);

// The mesh in force at plane `plane`.
const FrameMesh& mesh_at(const TrackResult& result, size_t plane);

// The mask's object pixels at width × height (a mask of the video's coded
// size is scaled as the frames are).
Mask mask_from_image(const Image& picture, uint32_t width, uint32_t height);

}  // namespace m4mesh
