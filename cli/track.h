// m4mesh track: a video in, a 2D mesh object out (video/track.h).
#pragma once

#include <cstdint>
#include <string>

namespace m4mesh {

struct TrackArgs {
  std::string input;
  std::string output;   // the 2D mesh stream
  std::string texture;  // the first frame as a PNG (empty: not written)
  std::string uniform;  // "WxH" pixel cells
  uint32_t nodes = 0;   // a content-based Delaunay mesh
  std::string mask;     // a PNG of the object in the first frame
  std::string frames;   // "A:B", both included
  uint32_t search = 16;
  int levels = -1;
  std::string reference = "first";
  std::string border = "follow";  // border nodes follow the content, or stay on the frame's edges
  double remesh = 3;              // TrackSettings::remesh_stretch
  uint32_t block = 0;
  std::string report;  // per-frame CSV
};
int run_track(const TrackArgs& args);

}  // namespace m4mesh
