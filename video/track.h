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
  uint32_t block = 0;  // block matching's block side; 0: the side giving as many blocks as nodes
  std::function<void(int64_t done, int64_t total)> progress;  // total 0: not known
};

// Luma PSNRs (dB) over the pixels the mesh covers in that frame.
struct TrackedFrame {
  int64_t frame = 0;       // in the video
  uint64_t bits = 0;       // its plane in the stream
  double coverage = 0;     // share of the frame's pixels the mesh covers
  double render_psnr = 0;  // the texture warped by this plane (what `m4mesh render` draws) against the frame
  double mesh_psnr = 0;    // the previous frame warped by the mesh's motion to this frame (NaN for the first)
  double block_psnr = 0;   // block matching with as many vectors (NaN for the first)
};

struct TrackResult {
  VideoInfo video;
  FrameMesh mesh;
  std::vector<std::vector<Point>> positions;  // per frame, by node, half pixels
  Image texture;                              // the first frame over the mesh's rectangle
  std::vector<uint8_t> stream;
  std::vector<TrackedFrame> frames;
  uint32_t block = 0, blocks = 0;  // block matching's side and its vectors a frame
  int levels = 0;                  // the tracker's pyramid levels
  std::vector<std::string> warnings;
};

TrackResult track_video(const std::string& path, const TrackSettings& settings);

// The mask's object pixels at width × height (a mask of the video's coded
// size is scaled as the frames are).
Mask mask_from_image(const Image& picture, uint32_t width, uint32_t height);

}  // namespace m4mesh
